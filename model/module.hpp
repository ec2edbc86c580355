// smql's modules: shared libraries of its own that keep heavy libraries out of the programs that do
// not need them (libsmql_http.so: OpenSSL and its kin; libsmql_media.so: GDAL, GStreamer and FFmpeg),
// loaded (dlopen) on first use.
#pragma once

#include <string>

namespace smql {

struct Module {
    void* entry = nullptr;  // the module's entry point, or null
    std::string failure;    // why there is none: where it looked and what each place said
};

// The module `file` and its entry `entry`, looked for in $SMQL_MODULE_DIR, beside the program or library
// that holds `anchor` (its installed place), at `built` (where the build tree holds it: null for none), in
// the installed library folder, then by name (the loader's own search). A module is opened once per
// process by its caller.
Module openModule(const char* file, const void* anchor, const char* built, const char* entry);

}  // namespace smql
