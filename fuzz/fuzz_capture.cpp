// The capture readers on arbitrary text and binary files: pose.txt (rgbd),
// TUM's rgb.txt / depth.txt / groundtruth.txt, COLMAP's text and binary
// models, transforms.json (nerfstudio) and detections.json. One source, six
// targets (SMQL_FUZZ_CAPTURE picks the layout at compile time).
//
// Each target keeps a small valid capture in a scratch folder (8x6 images,
// valid companion files) and replaces one file with the input; for layouts of
// several files the input's first byte picks which one, so every file is
// fuzzed with valid neighbours.
#include <array>
#include <string>

#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "fuzz/fuzz_support.hpp"
#include "ingest/capture/capture.hpp"
#include "ingest/capture/detections.hpp"
#include "model/error.hpp"

using namespace smql;

namespace {

constexpr int kWidth = 8, kHeight = 6;

struct Companion {
    const char* name;
    std::string valid;  // what the file holds when the input replaces another one
};

void writeImages(const fuzz::Scratch& dir, const std::vector<std::string>& colour,
                 const std::vector<std::string>& depth) {
    cv::Mat bgr(kHeight, kWidth, CV_8UC3, cv::Scalar(40, 90, 160));
    cv::Mat mm(kHeight, kWidth, CV_16U, cv::Scalar(1500));
    for (const std::string& name : colour) cv::imwrite(dir.write(name, ""), bgr);
    for (const std::string& name : depth) cv::imwrite(dir.write(name, ""), mm);
}

template <typename T>
void put(std::string& out, T value) {
    out.append(reinterpret_cast<const char*>(&value), sizeof(T));
}

std::string colmapCamerasBin() {
    std::string bin;
    put<std::uint64_t>(bin, 1);
    put<std::int32_t>(bin, 1);  // camera id
    put<std::int32_t>(bin, 1);  // PINHOLE
    put<std::uint64_t>(bin, kWidth);
    put<std::uint64_t>(bin, kHeight);
    for (double p : {10.0, 10.0, 4.0, 3.0}) put<double>(bin, p);
    return bin;
}

std::string colmapImagesBin() {
    std::string bin;
    put<std::uint64_t>(bin, 2);
    for (std::uint32_t id : {1u, 2u}) {
        put<std::uint32_t>(bin, id);
        for (double q : {1.0, 0.0, 0.0, 0.0}) put<double>(bin, q);
        for (double t : {0.1 * id, 0.0, 0.0}) put<double>(bin, t);
        put<std::uint32_t>(bin, 1);
        bin += (id == 1 ? std::string("a.png") : std::string("b.png")) + '\0';
        put<std::uint64_t>(bin, 1);  // one 2D point: x, y, point id
        put<double>(bin, 1.0);
        put<double>(bin, 2.0);
        put<std::uint64_t>(bin, 1);
    }
    return bin;
}

std::string colmapPointsBin() {
    std::string bin;
    put<std::uint64_t>(bin, 1);
    put<std::uint64_t>(bin, 1);  // point id
    for (double c : {0.5, 0.2, 2.0}) put<double>(bin, c);
    for (std::uint8_t c : {200, 100, 50}) put<std::uint8_t>(bin, c);
    put<double>(bin, 0.7);       // error
    put<std::uint64_t>(bin, 1);  // track: image id, point index
    put<std::uint32_t>(bin, 1);
    put<std::uint32_t>(bin, 0);
    return bin;
}

struct Layout {
    fuzz::Scratch dir;
    std::string root = dir.path("capture").string();
    std::vector<Companion> files;

    Layout() {
#if SMQL_FUZZ_CAPTURE == 1  // rgbd: pose.txt
        writeImages(dir, {"capture/color/1.png", "capture/color/2.png"},
                    {"capture/depth/1.png", "capture/depth/2.png"});
        files = {{"pose.txt", "0 0 0 0 0 0 1\n0.1 0 0 0 0 0 1\n"}};
#elif SMQL_FUZZ_CAPTURE == 2  // TUM
        writeImages(dir, {"capture/rgb/a.png"}, {"capture/depth/a.png"});
        files = {{"rgb.txt", "# rgb\n1.0 rgb/a.png\n2.0 rgb/a.png\n"},
                 {"depth.txt", "1.01 depth/a.png\n2.0 depth/a.png\n"},
                 {"groundtruth.txt", "1.0 0 0 0 0 0 0 1\n2.0 0.1 0 0 0 0 0 1\n"}};
#elif SMQL_FUZZ_CAPTURE == 3  // COLMAP text
        writeImages(dir, {"capture/images/a.png", "capture/images/b.png"}, {});
        files = {{"sparse/0/cameras.txt", "1 PINHOLE 8 6 10 10 4 3\n"},
                 {"sparse/0/images.txt", "1 1 0 0 0 0 0 0 1 a.png\n1.0 2.0 1\n2 1 0 0 0 0.1 0 0 1 b.png\n\n"},
                 {"sparse/0/points3D.txt", "1 0.5 0.2 2.0 200 100 50 0.7 1 0\n"}};
#elif SMQL_FUZZ_CAPTURE == 4  // COLMAP binary
        writeImages(dir, {"capture/images/a.png", "capture/images/b.png"}, {});
        files = {{"sparse/0/cameras.bin", colmapCamerasBin()},
                 {"sparse/0/images.bin", colmapImagesBin()},
                 {"sparse/0/points3D.bin", colmapPointsBin()}};
#elif SMQL_FUZZ_CAPTURE == 5  // nerfstudio
        writeImages(dir, {"capture/images/0.png", "capture/images/1.png"}, {"capture/depth/0.png"});
        files = {{"transforms.json", R"({"fl_x": 10, "w": 8, "h": 6, "frames": [
            {"file_path": "images/0.png", "depth_file_path": "depth/0.png",
             "transform_matrix": [[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}]})"}};
#else                         // detections.json: read against a capture of three 8x6 frames
        files = {{"detections.json", "[]"}};
#endif
        for (const Companion& file : files) dir.write("capture/" + std::string(file.name), file.valid);
    }
};

const Layout& layout() {
    static const Layout instance;
    return instance;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const Layout& capture = layout();
    std::string_view input = fuzz::bytesOf(data, size);
    std::size_t chosen = 0;
    if (capture.files.size() > 1) {
        if (input.empty()) return 0;
        chosen = static_cast<unsigned char>(input.front()) % capture.files.size();
        input.remove_prefix(1);
    }
    for (std::size_t i = 0; i < capture.files.size(); ++i)
        capture.dir.write("capture/" + std::string(capture.files[i].name),
                          i == chosen ? input : capture.files[i].valid);
    try {
#if SMQL_FUZZ_CAPTURE == 6
        ingest::Capture frames;
        frames.intrinsics = {kWidth, kHeight, 10, 10, 3.5, 2.5};
        for (int i = 1; i <= 3; ++i) {
            ingest::CaptureFrame frame;
            frame.index = i - 1;
            frame.colorPath = capture.root + "/color/" + std::to_string(i) + ".png";
            frames.frames.push_back(frame);
        }
        frames.detectionsPath = capture.root + "/detections.json";
        ingest::readDetections(frames);
#else
        ingest::readCapture(capture.root);
#endif
    } catch (const Error&) {
        // A user error: the expected outcome for most inputs.
    }
    return 0;
}
