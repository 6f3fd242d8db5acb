from typing import Any, Optional

import pandas

from ._core import (InputError as InputError, __version__ as __version__,
                    generator_settings as generator_settings, generators as generators,
                    git_commit as git_commit, read_dump as read_dump, settings as settings,
                    solve as solve, solvers as solvers, synthetic as synthetic)

def load_report(path: str, table: Optional[str] = None) -> pandas.DataFrame: ...
