// Base64 (RFC 4648, with padding): blobs in the scene JSON format, scripts in data: URLs.
#pragma once

#include <string>
#include <string_view>

namespace smql::model {

inline constexpr std::string_view kBase64Digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

std::string toBase64(std::string_view bytes);

}  // namespace smql::model
