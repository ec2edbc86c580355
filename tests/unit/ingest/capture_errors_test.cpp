// The capture readers' errors: every one names the file (and the line for
// text files) and is an Input error.
#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <string>

#include "capture_support.hpp"
#include "ingest/capture/capture.hpp"
#include "ingest/capture/capture_detail.hpp"
#include "ingest/capture/frame_loader.hpp"

using namespace smql;
using namespace smql::ingest;
using namespace smql::ingest::test;
using smql::ingest::capture_detail::storedImageSize;

namespace {

constexpr const char* kTransformsHead = R"({"fl_x": 50, "w": 40, "h": 30, "frames": [)";

void writeColmapModel(const TempDir& dir, const std::string& images) {
    dir.write("sparse/0/cameras.txt", "1 PINHOLE 40 30 50 50 20 15\n");
    dir.write("sparse/0/images.txt", images);
    dir.write("sparse/0/points3D.txt", "");
    writeColor(dir, "images/a.png", 40, 30);
    writeColor(dir, "images/b.png", 40, 30);
}

}  // namespace

TEST_CASE("capture errors: nothing to read", "[capture][errors]") {
    TempDir dir;
    SECTION("no such path") {
        requireError([&] { readCapture(dir.path("missing")); }, {dir.path("missing"), "no such file or folder"});
    }
    SECTION("empty folder") {
        requireError([&] { readCapture(dir.path()); }, {dir.path(), "empty"});
    }
    SECTION("unknown layout: the error lists what was looked for") {
        dir.write("readme.md", "hello");
        dir.mkdir("color");  // without depth/
        requireError([&] { readCapture(dir.path()); }, {dir.path(), "no capture layout recognised", "color/ and depth/",
                                                        "rgb.txt", "transforms.json", "sparse/0", ".png"});
    }
    SECTION("a single image") {
        std::string image = writeColor(dir, "a.png", 8, 8);
        requireError([&] { readCapture(image); }, {image, "single image"});
    }
    SECTION("a file that is not a video") {
        std::string file = dir.write("clip.mp4", "certainly not an mp4 file");
        requireError([&] { readCapture(file); }, {file, "not a video"});
    }
    SECTION("a bad fps option") {
        CaptureOptions options;
        options.fps = std::nan("");
        requireError([&] { readCapture(diningPath(), options); }, {"fps"}, std::nullopt, ErrorKind::Usage);
    }
}

TEST_CASE("rgbd: poses stay with their frames when a colour image is missing", "[capture][errors][rgbd]") {
    TempDir dir;
    writeRgbd(dir, 5);  // frame i's camera at x = 0.1 i

    SECTION("a colour image deleted from the middle: the frame is skipped, the later poses stay") {
        fs::remove(dir.path("color/3.png"));
        Capture capture = readCapture(dir.path());
        REQUIRE(capture.frames.size() == 4);
        for (const CaptureFrame& frame : capture.frames) {
            const long long number = std::stoll(fs::path(frame.colorPath).stem().string());
            CHECK(frame.pose->translation.x == Approx(0.1 * number));
        }
        CHECK(std::any_of(capture.notes.begin(), capture.notes.end(),
                          [](const std::string& n) { return n.find("frame 3): those frames are skipped") != n.npos; }));
    }
    SECTION("both images of a frame gone: a line for every number from the first to the last keeps them") {
        fs::remove(dir.path("color/3.png"));
        fs::remove(dir.path("depth/3.png"));
        Capture capture = readCapture(dir.path());
        REQUIRE(capture.frames.size() == 4);
        CHECK(capture.frames.back().pose->translation.x == Approx(0.5));
    }
    SECTION("both images of a frame gone and its line too: matched by frame order") {
        fs::remove(dir.path("color/3.png"));
        fs::remove(dir.path("depth/3.png"));
        dir.write("pose.txt", "0.1 0 0 0 0 0 1\n0.2 0 0 0 0 0 1\n0.4 0 0 0 0 0 1\n0.5 0 0 0 0 0 1\n");
        Capture capture = readCapture(dir.path());
        REQUIRE(capture.frames.size() == 4);
        CHECK(capture.frames.back().pose->translation.x == Approx(0.5));
    }
    SECTION("fewer lines than frames is an error, never a shift") {
        dir.write("pose.txt", "0.1 0 0 0 0 0 1\n0.2 0 0 0 0 0 1\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("pose.txt"), "2 pose line(s) for 5 frames"});
    }
}

TEST_CASE("images past 100 megapixels are refused on their header's word, before decoding", "[capture][errors]") {
    TempDir dir;
    writeRgbd(dir, 2);
    // A PNG's header stating 20000 x 20000 pixels (1.2 GB decoded), and nothing after it.
    std::string png("\x89PNG\r\n\x1a\n\0\0\0\x0dIHDR", 16);
    for (int side : {20000, 20000})
        for (int shift : {24, 16, 8, 0}) png += static_cast<char>((side >> shift) & 0xFF);
    png += std::string("\x08\x02\0\0\0", 5);
    dir.write("color/2.png", png);
    requireError([&] { readCapture(dir.path()); }, {dir.path("color/2.png"), "20000 x 20000 pixels", "100 megapixels"});
    // The sizes read from headers are the images' own.
    CHECK(storedImageSize(dir.path("color/1.png")) == std::pair{64, 48});
    cv::imwrite(dir.path("photo.jpg"), colorImage(320, 200));
    CHECK(storedImageSize(dir.path("photo.jpg")) == std::pair{320, 200});
    CHECK(storedImageSize(diningPath() + "/color/1.png") == std::pair{640, 480});
    // A JPEG's frame header after an EXIF segment of 60 KB, stepped over: a phone's photo.
    std::ifstream jpeg(dir.path("photo.jpg"), std::ios::binary);
    const std::string plain((std::istreambuf_iterator<char>(jpeg)), std::istreambuf_iterator<char>());
    std::string exif("\xFF\xE1", 2);
    const unsigned length = 60000;
    exif += static_cast<char>(length >> 8);
    exif += static_cast<char>(length & 0xFF);
    exif += std::string(length - 2, 'x');
    dir.write("exif.jpg", plain.substr(0, 2) + exif + plain.substr(2));
    CHECK(storedImageSize(dir.path("exif.jpg")) == std::pair{320, 200});
    CHECK(cv::imread(dir.path("exif.jpg")).size() == cv::Size(320, 200));
}

TEST_CASE("a PGM depth image past 100 megapixels is refused on its header's word", "[capture][errors][pgm]") {
    TempDir dir;
    writeRgbd(dir, 2);
    // A 16-bit PGM's header stating 20000 x 20000 pixels (800 MB decoded), a comment in it, and no pixels.
    fs::remove(dir.path("depth/2.png"));
    dir.write("depth/2.pgm", "P5\n# a depth camera\n20000 20000\n65535\n");
    requireError([&] { readCapture(dir.path()); }, {dir.path("depth/2.pgm"), "20000 x 20000 pixels", "100 megapixels"});
}

namespace {

// The first `bytes` of a file: a copy or a download that stopped.
std::string cutCopy(const TempDir& dir, const fs::path& from, const std::string& name, std::size_t bytes) {
    std::ifstream in(from, std::ios::binary);
    std::string content(bytes, '\0');
    in.read(content.data(), static_cast<std::streamsize>(bytes));
    content.resize(static_cast<std::size_t>(in.gcount()));
    return dir.write(name, content);
}

}  // namespace

TEST_CASE("image files that cannot be read are named together, before any is decoded", "[capture][errors]") {
    TempDir dir;
    const fs::path office = fs::path(SMQL_SHARED_DATA) / "captures" / "tum-fr3-office-photos";
    const std::string photo = (office / "1341847985.746954.png").string();
    SECTION("a folder of photos: empty, not an image, cut short") {
        for (const char* name : {"1341847980.722988.png", "1341847981.726650.png", "1341847982.730674.png"})
            fs::copy_file(office / name, dir.root() / name);
        const std::string empty = dir.write("empty.png", "");
        const std::string text = dir.write("notes.jpg", "not an image");
        const std::string cut = cutCopy(dir, photo, "half.png", fs::file_size(photo) / 2);
        requireError([&] { readCapture(dir.path()); }, {"3 image files cannot be read", empty + " (image is empty)",
                                                        text + " (image: not an image OpenCV can read",
                                                        cut + " (image cut short, a PNG without its end chunk"});
    }
    SECTION("a JPEG cut short is refused; one with a trailer after its end, as a phone's motion photo, is read") {
        std::vector<std::uint8_t> jpeg;
        cv::imencode(".jpg", cv::imread(photo), jpeg);
        const std::string whole(jpeg.begin(), jpeg.end());
        REQUIRE(whole.substr(whole.size() - 2) == "\xFF\xD9");
        const std::string cut = dir.write("cut.jpg", whole.substr(0, whole.size() / 2));
        CHECK(capture_detail::cutShort(cut) == "a JPEG without its end-of-image marker");
        const std::string motion = dir.write("motion.jpg", whole + "\0\0\0\x18" + "ftypmp42" + std::string(4096, 'v'));
        CHECK(capture_detail::cutShort(motion) == std::nullopt);
        CHECK(capture_detail::cutShort(photo) == std::nullopt);
        // OpenCV reads the cut one without an error, its lost half grey: it would be taken as it is.
        CHECK(!cv::imread(cut).empty());
    }
    SECTION("an RGB-D capture's colour and depth images cut short, named in one error") {
        for (const char* folder : {"color", "depth"}) fs::copy(fs::path(diningPath()) / folder, dir.root() / folder);
        fs::copy_file(fs::path(diningPath()) / "pose.txt", dir.root() / "pose.txt");
        const std::string colour = cutCopy(dir, diningPath() + "/color/3.png", "color/3.png", 20000);
        const std::string depth = cutCopy(dir, diningPath() + "/depth/4.pgm", "depth/4.pgm", 20000);
        requireError([&] { readCapture(dir.path()); },
                     {"2 image files cannot be read", colour + " (colour image cut short, a PNG without its end chunk",
                      depth + " (depth image cut short, a PGM of 640 x 480 pixels with 20000 of its"});
    }
}

TEST_CASE("capture errors: rgbd", "[capture][errors][rgbd]") {
    TempDir dir;
    writeRgbd(dir, 2);

    SECTION("a colour image without depth") {
        fs::remove(dir.path("depth/2.png"));
        requireError([&] { readCapture(dir.path()); },
                     {dir.path("depth"), "no depth image for frame 2", dir.path("color/2.png")});
    }
    SECTION("missing pose.txt") {
        fs::remove(dir.path("pose.txt"));
        requireError([&] { readCapture(dir.path()); }, {dir.path("pose.txt"), "missing"});
    }
    SECTION("a pose line that does not parse") {
        dir.write("pose.txt", "0 0 0 0 0 0 1\n0 0 zero 0 0 0 1\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("pose.txt") + ":2:", "'zero' is not a number"}, 2);
    }
    SECTION("a pose line with 6 numbers") {
        dir.write("pose.txt", "# header\n0 0 0 0 0 0 1\n0 0 0 0 0 1\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("pose.txt") + ":3:", "expected 7 numbers", "got 6"},
                     3);
    }
    SECTION("fewer pose lines than frames") {
        dir.write("pose.txt", "0 0 0 0 0 0 1\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("pose.txt"), "1 pose line(s) for 2 frames"});
    }
    SECTION("NaN in a pose") {
        dir.write("pose.txt", "nan 0 0 0 0 0 1\n0 0 0 0 0 0 1\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("pose.txt") + ":1:", "not finite"}, 1);
    }
    SECTION("a quaternion of zero norm") {
        dir.write("pose.txt", "0 0 0 0 0 0 1\n1 2 3 0 0 0 0\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("pose.txt") + ":2:", "zero norm"}, 2);
    }
    SECTION("an unreadable colour image") {
        dir.write("color/2.png", "this is not a PNG");
        requireError([&] { readCapture(dir.path()); }, {dir.path("color/2.png"), "not an image OpenCV can read"});
    }
    SECTION("a damaged first image (a PNG's signature and end, broken data between)") {
        dir.write("color/1.png", std::string("\x89PNG\r\n\x1a\n", 8) + "damaged" + std::string("\0\0\0\0IEND", 8));
        requireError([&] { readCapture(dir.path()); }, {dir.path("color/1.png"), "cannot decode"});
    }
    SECTION("a first image cut short (a PNG's signature, no end)") {
        dir.write("color/1.png", std::string("\x89PNG\r\n\x1a\n", 8) + "truncated");
        requireError([&] { readCapture(dir.path()); }, {dir.path("color/1.png"), "cut short"});
    }
    SECTION("a depth image of another aspect ratio: readCapture checks the first frame") {
        writeDepth(dir, "depth/1.png", 32, 30);
        requireError([&] { readCapture(dir.path()); },
                     {dir.path("depth/1.png"), "32x30", "64x48", dir.path("color/1.png"), "another aspect ratio"});
    }
    SECTION("a depth image of the colour's aspect ratio at half its size is registered to it") {
        writeDepth(dir, "depth/1.png", 32, 24);
        const Capture capture = readCapture(dir.path());
        CHECK(hasNote(capture, "32x24 images beside 64x48 colour"));
        CHECK(loadFrame(capture, capture.frames[0], 640).depth.size() == cv::Size(64, 48));
    }
    SECTION("a depth image of the wrong size: loadFrame checks every frame") {
        writeDepth(dir, "depth/2.png", 64, 40);
        Capture capture = readCapture(dir.path());
        requireError([&] { loadFrame(capture, capture.frames[1], 640); }, {dir.path("depth/2.png"), "64x40", "64x48"});
    }
    SECTION("loadFrame: an image removed after reading") {
        Capture capture = readCapture(dir.path());
        fs::remove(dir.path("color/2.png"));
        requireError([&] { loadFrame(capture, capture.frames[1], 640); }, {dir.path("color/2.png"), "missing"});
    }
    SECTION("an 8-bit depth image") {
        writeColor(dir, "depth/1.png", 64, 48);
        requireError([&] { readCapture(dir.path()); }, {dir.path("depth/1.png"), "one channel"});
    }
    SECTION("a bad camera.json") {
        dir.write("camera.json", R"({"width": 64, "height": 48, "fx": "525", "fy": 525, "cx": 32, "cy": 24})");
        requireError([&] { readCapture(dir.path()); }, {dir.path("camera.json"), "fx", "expected a number"});
    }
    SECTION("camera.json with a misspelt field") {
        dir.write("camera.json",
                  R"({"width": 64, "height": 48, "fx": 1, "fy": 1, "cx": 32, "cy": 24, "depthscale": 1})");
        requireError([&] { readCapture(dir.path()); }, {dir.path("camera.json"), "depthscale", "unknown field"});
    }
    SECTION("camera.json that is not JSON") {
        dir.write("camera.json", "{\"width\": 64,\n \"height\": }");
        requireError([&] { readCapture(dir.path()); }, {dir.path("camera.json") + ":2:", "not valid JSON"});
    }
    SECTION("camera.json for another aspect ratio") {
        dir.write("camera.json", R"({"width": 64, "height": 64, "fx": 1, "fy": 1, "cx": 32, "cy": 24})");
        requireError([&] { readCapture(dir.path()); }, {dir.path("color/1.png"), "64x48", "64x64"});
    }
    SECTION("an instance folder missing a mask") {
        writeDepth(dir, "instance/1.png", 64, 48);
        requireError([&] { readCapture(dir.path()); }, {dir.path("instance"), "no instance mask for frame 2"});
    }
    SECTION("two colour images for one frame") {
        writeColor(dir, "color/01.jpg", 64, 48);
        requireError([&] { readCapture(dir.path()); }, {"two colour images for frame 1"});
    }
    SECTION("a negative depth scale option") {
        CaptureOptions options;
        options.depthScale = -1;
        requireError([&] { readCapture(dir.path(), options); }, {"depth scale"}, std::nullopt, ErrorKind::Usage);
    }
}

TEST_CASE("capture errors: TUM", "[capture][errors][tum]") {
    TempDir dir;
    writeColor(dir, "rgb/a.png", 32, 24);
    writeDepth(dir, "depth/a.png", 32, 24);
    dir.write("rgb.txt", "# rgb\n1.0 rgb/a.png\n2.0 rgb/a.png\n");
    dir.write("depth.txt", "1.01 depth/a.png\n2.0 depth/a.png\n");
    dir.write("groundtruth.txt", "1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 0 1\n");
    REQUIRE(readCapture(dir.path()).frames.size() == 2);

    SECTION("a bad ground-truth line") {
        dir.write("groundtruth.txt", "# gt\n1.0 0 0 0 0 0 0 1\n2.0 0 0 0 0 0 1\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("groundtruth.txt") + ":3:", "expected 8 numbers"}, 3);
    }
    SECTION("a bad timestamp") {
        dir.write("rgb.txt", "1.0 rgb/a.png\nx2 rgb/a.png\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("rgb.txt") + ":2:", "'x2' is not a number"}, 2);
    }
    SECTION("no depth.txt") {
        fs::remove(dir.path("depth.txt"));
        requireError([&] { readCapture(dir.path()); }, {dir.path("depth.txt"), "missing"});
    }
    SECTION("no depth within 0.02 s") {
        dir.write("depth.txt", "5.0 depth/a.png\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("rgb.txt"), "no rgb frame has a depth image"});
    }
    SECTION("a listed image that does not exist") {
        dir.write("rgb.txt", "1.0 rgb/a.png\n2.0 rgb/b.png\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("rgb/b.png"), "missing"});
    }
}

TEST_CASE("capture errors: nerfstudio", "[capture][errors][nerfstudio]") {
    TempDir dir;
    writeColor(dir, "images/0.png", 40, 30);
    const std::string identity = R"([[1,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]])";

    SECTION("no frame whose image is there") {
        dir.write("transforms.json", std::string(kTransformsHead) +
                                         R"({"file_path": "images/9.png", "transform_matrix": )" + identity + "}]}");
        requireError([&] { readCapture(dir.path()); },
                     {dir.path("transforms.json"), "frames", "none of its 1 frames' images", dir.path("images/9.png")});
    }
    SECTION("frames whose image is missing are skipped, with a note") {
        dir.write("transforms.json", std::string(kTransformsHead) +
                                         R"({"file_path": "images/9.png", "transform_matrix": )" + identity +
                                         R"(}, {"file_path": "images/0.png", "transform_matrix": )" + identity + "}]}");
        Capture capture = readCapture(dir.path());
        REQUIRE(capture.frames.size() == 1);
        CHECK(fs::path(capture.frames[0].colorPath).filename() == "0.png");
        CHECK(std::any_of(capture.notes.begin(), capture.notes.end(), [](const std::string& n) {
            return n.find(
                       "1 of 2 frames listed have no image in the folder and are skipped (the first: images/9.png)") !=
                   std::string::npos;
        }));
    }
    SECTION("a transform that is not a rotation") {
        dir.write(
            "transforms.json",
            std::string(kTransformsHead) +
                R"({"file_path": "images/0.png", "transform_matrix": [[2,0,0,0],[0,1,0,0],[0,0,1,0],[0,0,0,1]]}]})");
        requireError([&] { readCapture(dir.path()); },
                     {dir.path("transforms.json"), "frames[0].transform_matrix", "not a rotation"});
    }
    SECTION("a 4x3 matrix") {
        dir.write("transforms.json",
                  std::string(kTransformsHead) +
                      R"({"file_path": "images/0.png", "transform_matrix": [[1,0,0],[0,1,0],[0,0,1]]}]})");
        requireError([&] { readCapture(dir.path()); }, {dir.path("transforms.json"), "frames[0].transform_matrix[0]"});
    }
    SECTION("no focal length") {
        dir.write(
            "transforms.json",
            R"({"w": 40, "h": 30, "frames": [{"file_path": "images/0.png", "transform_matrix": )" + identity + "}]}");
        requireError([&] { readCapture(dir.path()); }, {dir.path("transforms.json"), "frames[0]", "no focal length"});
    }
    SECTION("no frames") {
        dir.write("transforms.json", R"({"fl_x": 50, "frames": []})");
        requireError([&] { readCapture(dir.path()); }, {dir.path("transforms.json"), "frames", "no frames"});
    }
}

TEST_CASE("capture errors: COLMAP", "[capture][errors][colmap]") {
    TempDir dir;
    const std::string images = "# header\n1 1 0 0 0 0 0 0 1 a.png\n\n2 1 0 0 0 0 0 1 1 b.png\n1.0 2.0 -1\n";
    writeColmapModel(dir, images);
    REQUIRE(readCapture(dir.path()).frames.size() == 2);

    SECTION("images.txt without the 2D point lines") {
        writeColmapModel(dir, "1 1 0 0 0 0 0 0 1 a.png\n2 1 0 0 0 0 0 1 1 b.png\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("sparse/0/images.txt") + ":2:", "two lines"}, 2);
    }
    SECTION("images.txt with a short line") {
        writeColmapModel(dir, "1 1 0 0 0 0 0 1 a.png\n\n");
        requireError([&] { readCapture(dir.path()); },
                     {dir.path("sparse/0/images.txt") + ":1:", "IMAGE_ID QW QX QY QZ TX TY TZ CAMERA_ID NAME"}, 1);
    }
    SECTION("a zero quaternion in images.txt") {
        writeColmapModel(dir, "1 0 0 0 0 0 0 0 1 a.png\n\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("sparse/0/images.txt") + ":1:", "zero norm"}, 1);
    }
    SECTION("an unknown camera") {
        writeColmapModel(dir, "1 1 0 0 0 0 0 0 3 a.png\n\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("sparse/0/images.txt") + ":1", "camera 3"});
    }
    SECTION("an unsupported camera model") {
        dir.write("sparse/0/cameras.txt", "1 OPENCV_FISHEYE 40 30 50 50 20 15 0 0 0 0\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("sparse/0/cameras.txt") + ":1", "OPENCV_FISHEYE"});
    }
    SECTION("a camera with the wrong number of parameters") {
        dir.write("sparse/0/cameras.txt", "# cameras\n1 PINHOLE 40 30 50 20 15\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("sparse/0/cameras.txt") + ":2:", "takes 4 parameters"},
                     2);
    }
    SECTION("an image the image folder lacks") {
        fs::remove(dir.path("images/b.png"));
        requireError([&] { readCapture(dir.path()); }, {dir.path("sparse/0/images.txt") + ":4", "'b.png'"});
    }
    SECTION("no image folder") {
        fs::remove_all(dir.path("images"));
        requireError([&] { readCapture(dir.path()); }, {dir.path("sparse/0"), "cannot find the images"});
    }
    SECTION("a truncated images.bin") {
        std::string bin;
        put<std::uint64_t>(bin, 1);
        put<std::uint32_t>(bin, 1);
        put<double>(bin, 1.0);
        dir.write("bin/cameras.bin", std::string(8, '\0'));
        dir.write("bin/images.bin", bin);
        fs::create_directories(dir.path("images"));
        requireError([&] { readCapture(dir.path("bin")); }, {dir.path("bin/images.bin"), "too short"});
    }
    SECTION("a bad point line") {
        dir.write("sparse/0/points3D.txt", "1 0 0 0 300 0 0 0.1\n");
        requireError([&] { readCapture(dir.path()); }, {dir.path("sparse/0/points3D.txt") + ":1:", "0..255"}, 1);
    }
}
