#include "model/utf8.hpp"

namespace smql::model {

std::optional<std::size_t> invalidUtf8At(std::string_view text) {
    const auto* bytes = reinterpret_cast<const unsigned char*>(text.data());
    const std::size_t size = text.size();
    std::size_t i = 0;
    while (i < size) {
        const unsigned char lead = bytes[i];
        if (lead < 0x80) {
            ++i;
            continue;
        }
        // The length of the sequence and the range its second byte must lie in
        // (tighter than 80..BF where a wider range would allow overlong forms,
        // surrogates or code points above U+10FFFF).
        std::size_t length = 0;
        unsigned char low = 0x80, high = 0xBF;
        if (lead >= 0xC2 && lead <= 0xDF) {
            length = 2;
        } else if (lead >= 0xE0 && lead <= 0xEF) {
            length = 3;
            if (lead == 0xE0) low = 0xA0;
            if (lead == 0xED) high = 0x9F;
        } else if (lead >= 0xF0 && lead <= 0xF4) {
            length = 4;
            if (lead == 0xF0) low = 0x90;
            if (lead == 0xF4) high = 0x8F;
        } else {
            return i;
        }
        if (i + 1 >= size || bytes[i + 1] < low || bytes[i + 1] > high) return i;
        for (std::size_t k = 2; k < length; ++k)
            if (i + k >= size || (bytes[i + k] & 0xC0) != 0x80) return i;
        i += length;
    }
    return std::nullopt;
}

std::string escapeInvalidUtf8(std::string_view text) {
    static constexpr char kHex[] = "0123456789ABCDEF";
    std::string out;
    out.reserve(text.size());
    while (std::optional<std::size_t> bad = invalidUtf8At(text)) {
        const auto byte = static_cast<unsigned char>(text[*bad]);
        out.append(text.substr(0, *bad));
        out += "\\x";
        out += kHex[byte >> 4];
        out += kHex[byte & 15];
        text.remove_prefix(*bad + 1);
    }
    out.append(text);
    return out;
}

}  // namespace smql::model
