/* The SDK headers must compile as strict C99 (-std=c99 -pedantic -Werror):
 * plugin authors include them from plain C. */
#include <arbor/arbor.h>

#include <string.h>

int arbor_sdk_headers_c99_compile(void);
int arbor_sdk_headers_c99_compile(void)
{
    arbor_volume v;
    memset(&v, 0, sizeof v);
    v.struct_size = sizeof v;
    return (int)arbor_voxel_size(ARBOR_VOXEL_U16) + (int)v.struct_size +
           (int)ARBOR_HAS_FIELD(arbor_volume, v.struct_size, voxels) +
           (arbor_status_name(ARBOR_OK)[0] == 'o');
}
