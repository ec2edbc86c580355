#include "model/base64.hpp"

#include <cstdint>

namespace smql::model {

std::string toBase64(std::string_view bytes) {
    std::string out;
    out.reserve((bytes.size() + 2) / 3 * 4);
    for (std::size_t i = 0; i < bytes.size(); i += 3) {
        std::uint32_t chunk = std::uint32_t(std::uint8_t(bytes[i])) << 16;
        if (i + 1 < bytes.size()) chunk |= std::uint32_t(std::uint8_t(bytes[i + 1])) << 8;
        if (i + 2 < bytes.size()) chunk |= std::uint8_t(bytes[i + 2]);
        out += kBase64Digits[chunk >> 18 & 63];
        out += kBase64Digits[chunk >> 12 & 63];
        out += i + 1 < bytes.size() ? kBase64Digits[chunk >> 6 & 63] : '=';
        out += i + 2 < bytes.size() ? kBase64Digits[chunk & 63] : '=';
    }
    return out;
}

}  // namespace smql::model
