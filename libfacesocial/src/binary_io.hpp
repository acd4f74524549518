// Private little-endian binary reading and writing for model and bank files. Readers throw
// ModelFormatError("<stream>", ...) when the data runs out; file-level code rethrows with the path.
#pragma once

#include <cstdint>
#include <istream>
#include <ostream>
#include <string>
#include <vector>

#include "facesocial/error.hpp"

namespace facesocial::detail {

template <class T>
void put(std::ostream& out, const T& v) {
    out.write(reinterpret_cast<const char*>(&v), sizeof(T));
}

template <class T>
T get(std::istream& in, const char* what) {
    T v{};
    if (!in.read(reinterpret_cast<char*>(&v), sizeof(T))) throw ModelFormatError("<stream>", std::string(what) + " truncated");
    return v;
}

inline void put_bytes(std::ostream& out, const void* p, std::size_t n) {
    out.write(static_cast<const char*>(p), std::streamsize(n));
}

inline void get_bytes(std::istream& in, void* p, std::size_t n, const char* what) {
    if (!in.read(static_cast<char*>(p), std::streamsize(n))) throw ModelFormatError("<stream>", std::string(what) + " truncated");
}

inline void put_string(std::ostream& out, const std::string& s) {
    put<uint32_t>(out, uint32_t(s.size()));
    put_bytes(out, s.data(), s.size());
}

inline std::string get_string(std::istream& in, const char* what, std::size_t max_size = 1 << 20) {
    const uint32_t n = get<uint32_t>(in, what);
    if (n > max_size) throw ModelFormatError("<stream>", std::string(what) + " holds a string of " + std::to_string(n) + " bytes");
    std::string s(n, '\0');
    get_bytes(in, s.data(), n, what);
    return s;
}

/// 64-bit FNV-1a hash, the checksum of bank files.
inline uint64_t fnv1a64(const char* data, std::size_t n) {
    uint64_t h = 0xcbf29ce484222325ull;
    for (std::size_t i = 0; i < n; ++i) {
        h ^= uint8_t(data[i]);
        h *= 0x100000001b3ull;
    }
    return h;
}

}  // namespace facesocial::detail
