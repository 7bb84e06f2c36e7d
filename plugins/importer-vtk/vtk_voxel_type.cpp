// vtk_voxel_type.cpp - mapping VTK scalar type codes to SDK voxel types.
#include "vtk_voxel_type.hpp"

#include <vtkType.h>

#include <limits>

namespace arbor::importer_vtk {

arbor_voxel_type voxel_type_of(int vtk_type)
{
    switch (vtk_type) {
    case VTK_UNSIGNED_CHAR: return ARBOR_VOXEL_U8;
    case VTK_SIGNED_CHAR: return ARBOR_VOXEL_I8;
    // Plain char follows the platform's signedness, and so do its values.
    case VTK_CHAR: return std::numeric_limits<char>::is_signed ? ARBOR_VOXEL_I8 : ARBOR_VOXEL_U8;
    case VTK_UNSIGNED_SHORT: return ARBOR_VOXEL_U16;
    case VTK_SHORT: return ARBOR_VOXEL_I16;
    case VTK_UNSIGNED_INT: return ARBOR_VOXEL_U32;
    case VTK_INT: return ARBOR_VOXEL_I32;
    // long is 32 bits on some platforms, where it fits; elsewhere it does not.
    case VTK_LONG: return sizeof(long) == 4 ? ARBOR_VOXEL_I32 : ARBOR_VOXEL_UNKNOWN;
    case VTK_UNSIGNED_LONG: return sizeof(long) == 4 ? ARBOR_VOXEL_U32 : ARBOR_VOXEL_UNKNOWN;
    case VTK_FLOAT: return ARBOR_VOXEL_F32;
    case VTK_DOUBLE: return ARBOR_VOXEL_F64;
    default: return ARBOR_VOXEL_UNKNOWN;
    }
}

std::string vtk_type_name(int vtk_type)
{
    switch (vtk_type) {
    case VTK_VOID: return "void";
    case VTK_BIT: return "bit";
    case VTK_CHAR: return "char";
    case VTK_SIGNED_CHAR: return "signed char";
    case VTK_UNSIGNED_CHAR: return "unsigned char";
    case VTK_SHORT: return "short";
    case VTK_UNSIGNED_SHORT: return "unsigned short";
    case VTK_INT: return "int";
    case VTK_UNSIGNED_INT: return "unsigned int";
    case VTK_LONG: return "long";
    case VTK_UNSIGNED_LONG: return "unsigned long";
    case VTK_LONG_LONG: return "long long";
    case VTK_UNSIGNED_LONG_LONG: return "unsigned long long";
    case VTK_ID_TYPE: return "id type";
    case VTK_FLOAT: return "float";
    case VTK_DOUBLE: return "double";
    case VTK_STRING: return "string";
    default: return "VTK type " + std::to_string(vtk_type);
    }
}

} // namespace arbor::importer_vtk
