// CRC32C (Castagnoli), the checksum of every stored record (docs/storage.md).
// The SSE4.2 crc32 instruction when the CPU has it, else a table.
#pragma once

#include <cstdint>
#include <string_view>

namespace smql::storage {

// `crc` is the value returned for the bytes before these (0 to start), so a
// checksum can run over a key and then its record without copying them together.
std::uint32_t crc32c(std::string_view bytes, std::uint32_t crc = 0);

}  // namespace smql::storage
