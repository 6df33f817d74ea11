#pragma once
// Checks a PLY file before assimp reads it. assimp 5.2's PLY reader trusts the file: it never
// returns on a header without `end_header`, writes past its arrays when an element is declared
// twice, and allocates what the header's element counts and the data's list lengths declare
// before reading them, so a file of a few hundred bytes could take many GiB (each of these was
// found by the fuzzers: docs/robustness.md). No GL, no assimp: plain file reading.

#include <cstdint>
#include <filesystem>

namespace penumbra {

// Throws ModelError, naming the file and what is wrong, when `file` starts with "ply" (in any
// case: assimp reads such a file as PLY whatever its extension) and:
// - its header has no `end_header` line in its first 64 KiB;
// - a header line is none of the format's (format, comment, obj_info, element, property), or
//   names a format or type the format does not have, or an element gives no count;
// - its header declares an element name twice;
// - its data cannot hold what the header declares: every element instance, and every list's
//   values as its length says (binary files: the bytes of each value; ASCII files: a number for
//   each value). Counts are read as assimp reads them: an element whose name assimp does not
//   know takes its count from the digits its name starts with.
// Files that do not start with "ply" are left alone.
void checkPlyFile(const std::filesystem::path& file, std::uintmax_t fileBytes);

}  // namespace penumbra
