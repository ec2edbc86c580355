// smql.h must be usable from C++ as is: C linkage, no C-only constructs.
#include "smql.h"

#include <type_traits>

static_assert(std::is_same_v<decltype(&smql_open), smql_status (*)(const char*, int, smql_db**)>);
static_assert(std::is_standard_layout_v<smql_box> && sizeof(smql_box) == 7 * sizeof(double));
