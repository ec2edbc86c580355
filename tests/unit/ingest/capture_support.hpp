// Helpers for the capture reader tests: temporary folders, small synthetic
// images and error assertions.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include <catch2/catch.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "ingest/capture/capture.hpp"
#include "model/error.hpp"

namespace smql::ingest::test {

namespace fs = std::filesystem;

inline std::string diningPath() { return std::string(SMQL_SHARED_DATA) + "/rgbd-dining"; }

// What one of the frames' decoders made of `file` (frame_decoders.hpp) is what OpenCV reads (cv::imdecode
// with `flags`): the same type, size and pixels.
inline void requireAsOpenCvReads(const std::optional<cv::Mat>& ours, const std::vector<std::uint8_t>& file, int flags) {
    const cv::Mat theirs = cv::imdecode(file, flags);
    REQUIRE(ours);
    REQUIRE(!theirs.empty());
    REQUIRE(ours->type() == theirs.type());
    REQUIRE(ours->size() == theirs.size());
    CHECK(cv::norm(*ours, theirs, cv::NORM_INF) == 0);
}

// Whether one of the capture's notes holds `fragment`.
inline bool hasNote(const Capture& capture, const std::string& fragment) {
    return std::any_of(capture.notes.begin(), capture.notes.end(),
                       [&](const std::string& note) { return note.find(fragment) != std::string::npos; });
}

// A fresh folder under the system temp folder, removed with everything in it.
class TempDir {
public:
    TempDir() {
        std::string pattern = (fs::temp_directory_path() / "smql-capture-XXXXXX").string();
        if (!mkdtemp(pattern.data())) throw std::runtime_error("mkdtemp failed");
        path_ = pattern;
    }
    ~TempDir() {
        std::error_code ignored;
        fs::remove_all(path_, ignored);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;

    const fs::path& root() const { return path_; }
    std::string path(const std::string& name = {}) const {
        return name.empty() ? path_.string() : (path_ / name).string();
    }
    std::string write(const std::string& name, const std::string& content) const {
        fs::path file = path_ / name;
        fs::create_directories(file.parent_path());
        std::ofstream(file, std::ios::binary) << content;
        return file.string();
    }
    std::string mkdir(const std::string& name) const {
        fs::create_directories(path_ / name);
        return path(name);
    }

private:
    fs::path path_;
};

// A BGR image whose pixels encode their position (so resampling is visible).
inline cv::Mat colorImage(int width, int height, int seed = 0) {
    cv::Mat image(height, width, CV_8UC3);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x)
            image.at<cv::Vec3b>(y, x) =
                cv::Vec3b(static_cast<uchar>((x * 4 + seed) % 256), static_cast<uchar>((y * 4 + seed) % 256),
                          static_cast<uchar>(seed % 256));
    return image;
}

inline std::string writeColor(const TempDir& dir, const std::string& name, int width, int height, int seed = 0) {
    fs::path file = dir.root() / name;
    fs::create_directories(file.parent_path());
    REQUIRE(cv::imwrite(file.string(), colorImage(width, height, seed)));
    return file.string();
}

// A 16-bit depth image: value = base + x (units of 1/depth_scale m).
inline std::string writeDepth(const TempDir& dir, const std::string& name, int width, int height,
                              std::uint16_t base = 1000) {
    cv::Mat depth(height, width, CV_16U);
    for (int y = 0; y < height; ++y)
        for (int x = 0; x < width; ++x) depth.at<std::uint16_t>(y, x) = static_cast<std::uint16_t>(base + x);
    fs::path file = dir.root() / name;
    fs::create_directories(file.parent_path());
    REQUIRE(cv::imwrite(file.string(), depth));
    return file.string();
}

// An rgbd capture of `frames` frames (1.png ... n.png), identity poses moving along x.
inline void writeRgbd(const TempDir& dir, int frames, int width = 64, int height = 48) {
    std::string poses;
    for (int i = 1; i <= frames; ++i) {
        writeColor(dir, "color/" + std::to_string(i) + ".png", width, height, i);
        writeDepth(dir, "depth/" + std::to_string(i) + ".png", width, height);
        poses += std::to_string(0.1 * i) + " 0 0 0 0 0 1\n";
    }
    dir.write("pose.txt", poses);
}

// `read` must throw an Error of `kind` whose message contains every fragment,
// and, when given, whose location is that line.
template <typename Read>
void requireError(Read&& read, std::initializer_list<std::string> fragments, std::optional<int> line = std::nullopt,
                  ErrorKind kind = ErrorKind::Input) {
    try {
        read();
    } catch (const Error& e) {
        INFO("message: " << e.message());
        CHECK(e.kind() == kind);
        for (const std::string& fragment : fragments) CHECK(e.message().find(fragment) != std::string::npos);
        if (line) {
            REQUIRE(e.where().has_value());
            CHECK(e.where()->line == *line);
        }
        return;
    }
    FAIL("no error thrown");
}

// Little-endian binary writing (COLMAP models).
template <typename T>
void put(std::string& out, T value) {
    char bytes[sizeof(T)];
    std::memcpy(bytes, &value, sizeof(T));
    out.append(bytes, sizeof(T));
}

}  // namespace smql::ingest::test
