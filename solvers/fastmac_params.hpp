#pragma once
// `fastmac`'s settings: a plain struct; its rows (CLI option, range, help, Python keyword) are
// declared in fastmac_solver.cpp. Its MAC stage takes the mac-* settings.

namespace verifybench {

/// FastMAC (Zhang et al., CVPR 2024).
struct FastMacParams {
  double ratio = 0.1;  ///< fraction of the correspondences the spectral sampling keeps
};

}  // namespace verifybench
