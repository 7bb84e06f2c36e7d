// voxel_type.hpp - mapping between the SDK's voxel type codes and C++ types.
//
// Algorithms are templates over the voxel type; dispatch_voxel_type switches
// on the runtime code once and calls the matching instantiation (the TTK
// pattern: one switch at the boundary, no virtual calls per voxel).
#pragma once

#include <arbor/volume.h>

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>

namespace arbor {

template <class T> struct VoxelCode;
template <> struct VoxelCode<uint8_t> { static constexpr arbor_voxel_type value = ARBOR_VOXEL_U8; };
template <> struct VoxelCode<int8_t> { static constexpr arbor_voxel_type value = ARBOR_VOXEL_I8; };
template <> struct VoxelCode<uint16_t> { static constexpr arbor_voxel_type value = ARBOR_VOXEL_U16; };
template <> struct VoxelCode<int16_t> { static constexpr arbor_voxel_type value = ARBOR_VOXEL_I16; };
template <> struct VoxelCode<uint32_t> { static constexpr arbor_voxel_type value = ARBOR_VOXEL_U32; };
template <> struct VoxelCode<int32_t> { static constexpr arbor_voxel_type value = ARBOR_VOXEL_I32; };
template <> struct VoxelCode<float> { static constexpr arbor_voxel_type value = ARBOR_VOXEL_F32; };
template <> struct VoxelCode<double> { static constexpr arbor_voxel_type value = ARBOR_VOXEL_F64; };

template <class T> inline constexpr arbor_voxel_type voxel_code_v = VoxelCode<T>::value;

// Calls f(T{}) with T the C++ type of `type`; throws for an unknown code.
template <class F>
decltype(auto) dispatch_voxel_type(arbor_voxel_type type, F &&f)
{
    switch (type) {
    case ARBOR_VOXEL_U8: return f(uint8_t{});
    case ARBOR_VOXEL_I8: return f(int8_t{});
    case ARBOR_VOXEL_U16: return f(uint16_t{});
    case ARBOR_VOXEL_I16: return f(int16_t{});
    case ARBOR_VOXEL_U32: return f(uint32_t{});
    case ARBOR_VOXEL_I32: return f(int32_t{});
    case ARBOR_VOXEL_F32: return f(float{});
    case ARBOR_VOXEL_F64: return f(double{});
    default: throw std::invalid_argument("unknown voxel type code " + std::to_string(type));
    }
}

// Voxel type from its short name ("u8", "i16", "f32"...); UNKNOWN if none.
inline arbor_voxel_type voxel_type_from_name(std::string_view name)
{
    for (arbor_voxel_type t = ARBOR_VOXEL_U8; t <= ARBOR_VOXEL_F64; ++t)
        if (name == arbor_voxel_type_name(t))
            return t;
    return ARBOR_VOXEL_UNKNOWN;
}

inline bool is_integer_voxel_type(arbor_voxel_type t)
{
    return t >= ARBOR_VOXEL_U8 && t <= ARBOR_VOXEL_I32;
}

} // namespace arbor
