// Shared by the fuzz targets: a scratch folder for the files the readers
// take by path, and the rule for what counts as a finding.
//
// The readers' contract is that anything wrong with their input is an
// smql::Error. Any other exception escaping them, a sanitizer report, a crash
// or a hang is a finding: the targets catch smql::Error only.
#pragma once

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <string_view>

namespace smql::fuzz {

namespace fs = std::filesystem;

// A folder of its own per process, under /dev/shm when there is one (the
// readers take paths, and a file written per input should cost no disk I/O),
// removed at exit.
class Scratch {
public:
    Scratch() {
        std::error_code ec;
        fs::path base = fs::is_directory("/dev/shm", ec) ? fs::path("/dev/shm") : fs::temp_directory_path();
        std::string pattern = (base / "smql-fuzz-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
        root_ = pattern;
    }
    ~Scratch() {
        std::error_code ec;
        fs::remove_all(root_, ec);
    }
    Scratch(const Scratch&) = delete;
    Scratch& operator=(const Scratch&) = delete;

    fs::path path(const std::string& name) const { return root_ / name; }
    std::string write(const std::string& name, std::string_view bytes) const {
        fs::path file = root_ / name;
        fs::create_directories(file.parent_path());
        std::ofstream(file, std::ios::binary | std::ios::trunc)
            .write(bytes.data(), static_cast<std::streamsize>(bytes.size()));
        return file.string();
    }

private:
    fs::path root_;
};

inline std::string_view bytesOf(const std::uint8_t* data, std::size_t size) {
    return {reinterpret_cast<const char*>(data), size};
}

}  // namespace smql::fuzz
