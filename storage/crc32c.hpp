// CRC32C (Castagnoli), the checksum of every stored record (docs/storage.md).
// The SSE4.2 crc32 instruction when the CPU has it, else a table.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string_view>

namespace smql::storage {

// `crc` is the value returned for the bytes before these (0 to start), so a
// checksum can run over a key and then its record without copying them together.
std::uint32_t crc32c(std::string_view bytes, std::uint32_t crc = 0);

// crc32c of `count` runs of `length` bytes, run i starting at `first + i * stride`, each after
// the bytes whose value is `crc`, into out[i]. The same values as one call per run, computed four
// runs side by side (the entries of an index page, checked as they are read).
void crc32cOfRuns(const char* first, std::size_t stride, std::size_t length, std::size_t count, std::uint32_t crc,
                  std::uint32_t* out);

}  // namespace smql::storage
