#include "storage/crc32c.hpp"

#include <array>
#include <cstring>

#if defined(__x86_64__)
#include <nmmintrin.h>
#endif

namespace smql::storage {

namespace {

constexpr std::uint32_t kPolynomial = 0x82F63B78;  // Castagnoli, bit-reflected

constexpr std::array<std::uint32_t, 256> makeTable() {
    std::array<std::uint32_t, 256> table{};
    for (std::uint32_t i = 0; i < 256; ++i) {
        std::uint32_t c = i;
        for (int bit = 0; bit < 8; ++bit) c = (c >> 1) ^ (c & 1 ? kPolynomial : 0);
        table[i] = c;
    }
    return table;
}

constexpr auto kTable = makeTable();

std::uint32_t tableCrc(const unsigned char* p, std::size_t n, std::uint32_t c) {
    for (std::size_t i = 0; i < n; ++i) c = kTable[(c ^ p[i]) & 0xff] ^ (c >> 8);
    return c;
}

#if defined(__x86_64__)
// Shifting a CRC over `len` zero bytes is a linear map of its 32 bits (GF(2)): as tables of the map
// applied to each byte of the CRC, the CRC of three runs computed side by side can be joined into
// the CRC of the runs one after another (Mark Adler's crc32c.c does it this way). The tables are made
// by the compiler: made on the first checksum of a long run, they took 95 us of a process's first
// query.
class ZeroShift {
public:
    constexpr explicit ZeroShift(std::size_t len) {
        const Matrix op = zerosOperator(len);
        for (std::uint32_t n = 0; n < 256; ++n)
            for (int byte = 0; byte < 4; ++byte) table_[byte][n] = times(op, n << (8 * byte));
    }
    std::uint32_t operator()(std::uint32_t crc) const {
        return table_[0][crc & 0xff] ^ table_[1][(crc >> 8) & 0xff] ^ table_[2][(crc >> 16) & 0xff] ^
               table_[3][crc >> 24];
    }

private:
    using Matrix = std::array<std::uint32_t, 32>;
    static constexpr std::uint32_t times(const Matrix& mat, std::uint32_t vec) {
        std::uint32_t sum = 0;
        for (int i = 0; vec; ++i, vec >>= 1)
            if (vec & 1) sum ^= mat[i];
        return sum;
    }
    static constexpr Matrix squared(const Matrix& mat) {
        Matrix out{};
        for (int n = 0; n < 32; ++n) out[n] = times(mat, mat[n]);
        return out;
    }
    // The map of `len` zero bytes (a power of two): one zero bit, squared up to eight, then once
    // per halving of len.
    static constexpr Matrix zerosOperator(std::size_t len) {
        Matrix op{};
        op[0] = kPolynomial;
        for (int n = 1; n < 32; ++n) op[n] = std::uint32_t(1) << (n - 1);
        for (int bits = 1; bits < 8; bits *= 2) op = squared(op);
        for (; len > 1; len >>= 1) op = squared(op);
        return op;
    }
    std::array<std::array<std::uint32_t, 256>, 4> table_{};
};

// Runs of these lengths are checksummed three at a time: the crc32 instruction takes three cycles
// but starts one a cycle, so three independent runs keep it busy (a scene index is ~125 KB).
constexpr std::size_t kLongRun = 8192, kShortRun = 256;
constexpr ZeroShift kLongShift(kLongRun), kShortShift(kShortRun);

__attribute__((target("sse4.2"))) std::uint64_t crcRuns(const unsigned char*& p, std::size_t& n, std::uint64_t c,
                                                        std::size_t run, const ZeroShift& shift) {
    for (; n >= 3 * run; p += 3 * run, n -= 3 * run) {
        std::uint64_t c1 = 0, c2 = 0;
        for (std::size_t i = 0; i < run; i += 8) {
            std::uint64_t w0, w1, w2;
            std::memcpy(&w0, p + i, 8);
            std::memcpy(&w1, p + run + i, 8);
            std::memcpy(&w2, p + 2 * run + i, 8);
            c = _mm_crc32_u64(c, w0);
            c1 = _mm_crc32_u64(c1, w1);
            c2 = _mm_crc32_u64(c2, w2);
        }
        c = shift(static_cast<std::uint32_t>(c)) ^ c1;
        c = shift(static_cast<std::uint32_t>(c)) ^ c2;
    }
    return c;
}

// Eight bytes per instruction: a 125-byte node record costs ~16 instructions,
// so checking every record on decode stays a small part of a lookup.
__attribute__((target("sse4.2"))) std::uint32_t hardwareCrc(const unsigned char* p, std::size_t n, std::uint32_t c) {
    std::uint64_t c64 = c;
    if (n >= 3 * kShortRun) {
        c64 = crcRuns(p, n, c64, kLongRun, kLongShift);
        c64 = crcRuns(p, n, c64, kShortRun, kShortShift);
    }
    for (; n >= 8; p += 8, n -= 8) {
        std::uint64_t word;
        std::memcpy(&word, p, 8);
        c64 = _mm_crc32_u64(c64, word);
    }
    c = static_cast<std::uint32_t>(c64);
    for (; n > 0; ++p, --n) c = _mm_crc32_u8(c, *p);
    return c;
}

// Four runs of one length at once: four independent chains of crc32 instructions, where one run
// alone waits three cycles for each.
__attribute__((target("sse4.2"))) void hardwareCrcOfFourRuns(const unsigned char* p, std::size_t stride,
                                                             std::size_t length, std::uint32_t c, std::uint32_t* out) {
    std::uint64_t c0 = c, c1 = c, c2 = c, c3 = c;
    std::size_t i = 0;
    for (; i + 8 <= length; i += 8) {
        std::uint64_t w0, w1, w2, w3;
        std::memcpy(&w0, p + i, 8);
        std::memcpy(&w1, p + stride + i, 8);
        std::memcpy(&w2, p + 2 * stride + i, 8);
        std::memcpy(&w3, p + 3 * stride + i, 8);
        c0 = _mm_crc32_u64(c0, w0);
        c1 = _mm_crc32_u64(c1, w1);
        c2 = _mm_crc32_u64(c2, w2);
        c3 = _mm_crc32_u64(c3, w3);
    }
    std::array<std::uint32_t, 4> tail{static_cast<std::uint32_t>(c0), static_cast<std::uint32_t>(c1),
                                      static_cast<std::uint32_t>(c2), static_cast<std::uint32_t>(c3)};
    for (std::size_t run = 0; run < 4; ++run) {
        for (std::size_t at = i; at < length; ++at) tail[run] = _mm_crc32_u8(tail[run], p[run * stride + at]);
        out[run] = tail[run];
    }
}

const bool kHaveSse42 = __builtin_cpu_supports("sse4.2");
#endif

}  // namespace

std::uint32_t crc32c(std::string_view bytes, std::uint32_t crc) {
    const auto* p = reinterpret_cast<const unsigned char*>(bytes.data());
    std::uint32_t c = ~crc;
#if defined(__x86_64__)
    if (kHaveSse42) return ~hardwareCrc(p, bytes.size(), c);
#endif
    return ~tableCrc(p, bytes.size(), c);
}

void crc32cOfRuns(const char* first, std::size_t stride, std::size_t length, std::size_t count, std::uint32_t crc,
                  std::uint32_t* out) {
    const auto* p = reinterpret_cast<const unsigned char*>(first);
    std::size_t i = 0;
#if defined(__x86_64__)
    if (kHaveSse42)
        for (; i + 4 <= count; i += 4) {
            hardwareCrcOfFourRuns(p + i * stride, stride, length, ~crc, out + i);
            for (std::size_t run = i; run < i + 4; ++run) out[run] = ~out[run];
        }
#endif
    for (; i < count; ++i) out[i] = crc32c(std::string_view(first + i * stride, length), crc);
}

}  // namespace smql::storage
