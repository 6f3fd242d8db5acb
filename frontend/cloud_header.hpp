#pragma once
// Header checks of .pcd and .ply files, made before PCL's readers see them (cloud_io.cpp). Each
// throws InputError naming the file, the header line where it can and what is wrong: no header,
// unknown keys, counts that are not non-negative integers, fields without x/y/z, face elements or
// property lists, or more data promised than the file holds (so no reader allocates for it).
#include <string>

namespace verifybench {

void check_pcd_header(const std::string& path);
void check_ply_header(const std::string& path);

}  // namespace verifybench
