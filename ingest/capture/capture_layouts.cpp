// The capture layouts, one table. Adding a layout is its file, which defines a CaptureLayout named
// k<Name>Layout (how to recognise it and its reader), and one line in SMQL_CAPTURE_LAYOUTS below:
// the order is the order readCapture tries them (docs/formats.md), and the shell's hint and the
// error for a path no layout recognises are made from the rows.
#include <fmt/format.h>

#include "ingest/capture/capture_detail.hpp"

#define SMQL_CAPTURE_LAYOUTS(X) \
    X(kRgbdLayout)              \
    X(kTumLayout)               \
    X(kNerfstudioLayout)        \
    X(kColmapLayout)            \
    X(kImageFolderLayout)       \
    X(kVideoLayout)

namespace smql::ingest::capture_detail {

#define SMQL_DECLARE_LAYOUT(layout) extern const CaptureLayout layout;
SMQL_CAPTURE_LAYOUTS(SMQL_DECLARE_LAYOUT)
#undef SMQL_DECLARE_LAYOUT

const std::vector<const CaptureLayout*>& captureLayouts() {
#define SMQL_LIST_LAYOUT(layout) &layout,
    static const std::vector<const CaptureLayout*> layouts{SMQL_CAPTURE_LAYOUTS(SMQL_LIST_LAYOUT)};
#undef SMQL_LIST_LAYOUT
    return layouts;
}

const std::string& layoutsHint() {
    static const std::string hint = [] {
        std::string out = "smql reads: ";
        const auto& layouts = captureLayouts();
        for (std::size_t i = 0; i < layouts.size(); ++i)
            out += fmt::format("{}{}", i == 0 ? "" : i + 1 == layouts.size() ? ", or " : ", ", layouts[i]->reads);
        return out;
    }();
    return hint;
}

bool isDirectory(const fs::path& path) {
    std::error_code ec;
    return fs::is_directory(path, ec);
}

bool isFile(const fs::path& path) {
    std::error_code ec;
    return fs::is_regular_file(path, ec);
}

}  // namespace smql::ingest::capture_detail
