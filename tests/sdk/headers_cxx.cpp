// The SDK headers (and the optional C++ layer) must compile as C++ with
// -pedantic -Werror: C++ plugins and the host include them.
#include <arbor/arbor.h>
#include <arbor/param_check.h>
#include <arbor/sdk/filter.hpp>
#include <arbor/sdk/importer.hpp>

static_assert(sizeof(arbor_status) == 4);
static_assert(ARBOR_ABI_VERSION_MAJOR >= 1);

int arbor_sdk_headers_cxx_compile()
{
    arbor_volume v{};
    v.struct_size = sizeof v;
    return static_cast<int>(arbor_voxel_size(ARBOR_VOXEL_F64) + v.struct_size);
}
