// JPEGs with an EXIF block, made with libexif, for the tests of what smql
// reads from a photo's EXIF (its camera, its orientation).
#pragma once

#include <cstdlib>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <libexif/exif-data.h>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>

#include "capture_support.hpp"

namespace smql::ingest::test {

// The tags to write; absent ones are left out of the block.
struct ExifTags {
    std::optional<int> focal35mm = std::nullopt;  // FocalLengthIn35mmFilm
    // Orientation: 6 = stored lying on its side, to be turned 90 degrees clockwise for viewing.
    std::optional<int> orientation = std::nullopt;
};

// `image` as dir/name, a JPEG whose EXIF block holds `tags`.
inline std::string writeExifJpeg(const TempDir& dir, const std::string& name, const cv::Mat& image,
                                 const ExifTags& tags) {
    std::vector<uchar> encoded;
    REQUIRE(cv::imencode(".jpg", image, encoded));
    const std::string jpeg(encoded.begin(), encoded.end());

    ExifData* exif = exif_data_new();
    exif_data_set_byte_order(exif, EXIF_BYTE_ORDER_INTEL);
    auto addShort = [&](ExifIfd ifd, ExifTag tag, int value) {
        ExifEntry* entry = exif_entry_new();
        exif_content_add_entry(exif->ifd[ifd], entry);
        exif_entry_initialize(entry, tag);
        exif_set_short(entry->data, EXIF_BYTE_ORDER_INTEL, static_cast<ExifShort>(value));
        exif_entry_unref(entry);
    };
    if (tags.focal35mm) addShort(EXIF_IFD_EXIF, EXIF_TAG_FOCAL_LENGTH_IN_35MM_FILM, *tags.focal35mm);
    if (tags.orientation) addShort(EXIF_IFD_0, EXIF_TAG_ORIENTATION, *tags.orientation);
    unsigned char* block = nullptr;
    unsigned int size = 0;
    exif_data_save_data(exif, &block, &size);
    exif_data_unref(exif);
    REQUIRE(block != nullptr);

    // APP1 right after the start-of-image marker: FF E1, its length (big-endian, counting itself), the block.
    std::string app1 = "\xFF\xE1";
    app1 += static_cast<char>(((size + 2) >> 8) & 0xFF);
    app1 += static_cast<char>((size + 2) & 0xFF);
    app1.append(reinterpret_cast<const char*>(block), size);
    free(block);
    return dir.write(name, jpeg.substr(0, 2) + app1 + jpeg.substr(2));
}

// A dark image with a bright 16-pixel square in its top-left corner: the corner the square ends up in,
// with the size, tells how the image was turned (90 degrees clockwise puts it top right).
inline cv::Mat markedImage(int width, int height) {
    cv::Mat image(height, width, CV_8UC3, cv::Scalar(40, 40, 40));
    image(cv::Rect(0, 0, 16, 16)).setTo(cv::Scalar(255, 255, 255));
    return image;
}

// The corner of `image` whose 16-pixel square is brightest: "top-left", "top-right", "bottom-left" or
// "bottom-right".
inline std::string brightCorner(const cv::Mat& image) {
    const int right = image.cols - 16, bottom = image.rows - 16;
    const std::pair<const char*, cv::Rect> corners[] = {{"top-left", {0, 0, 16, 16}},
                                                        {"top-right", {right, 0, 16, 16}},
                                                        {"bottom-left", {0, bottom, 16, 16}},
                                                        {"bottom-right", {right, bottom, 16, 16}}};
    std::string brightest;
    double best = -1;
    for (const auto& [name, square] : corners) {
        double value = cv::mean(image(square))[0];
        if (value > best) {
            best = value;
            brightest = name;
        }
    }
    return brightest;
}

}  // namespace smql::ingest::test
