#include "volume_textures.hpp"

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace arbor::glraycast {

namespace {

void nearest(GLenum target)
{
    glTexParameteri(target, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(target, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexParameteri(target, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    glTexParameteri(target, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    if (target == GL_TEXTURE_3D)
        glTexParameteri(target, GL_TEXTURE_WRAP_R, GL_CLAMP_TO_EDGE);
}

void texture_3d(Texture &t, GLint internal, GLenum format, GLenum type, const std::array<int64_t, 3> &dims,
                const void *data, bool linear = false)
{
    if (!t)
        t = make_texture();
    glBindTexture(GL_TEXTURE_3D, t.get());
    nearest(GL_TEXTURE_3D);
    if (linear) {
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
        glTexParameteri(GL_TEXTURE_3D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    }
    glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    glTexImage3D(GL_TEXTURE_3D, 0, internal, static_cast<GLsizei>(dims[0]), static_cast<GLsizei>(dims[1]),
                 static_cast<GLsizei>(dims[2]), 0, format, type, data);
}

std::array<int64_t, 3> dims_of(const raycast::VoxelGrid &g)
{
    return {g.nx, g.ny, g.nz};
}

void texture_2d(Texture &t, GLint internal, GLsizei w, GLsizei h, GLenum format, const float *data)
{
    if (!t)
        t = make_texture();
    glBindTexture(GL_TEXTURE_2D, t.get());
    nearest(GL_TEXTURE_2D);
    glTexImage2D(GL_TEXTURE_2D, 0, internal, w, h, 0, format, GL_FLOAT, data);
}

} // namespace

void VolumeTextures::upload_volume(const raycast::VoxelGrid &g)
{
    GLint largest = 0;
    glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &largest);
    if (g.nx > largest || g.ny > largest || g.nz > largest)
        throw std::runtime_error("the volume (" + std::to_string(g.nx) + " x " + std::to_string(g.ny) + " x " +
                                 std::to_string(g.nz) + ") exceeds this OpenGL's 3D texture size of " +
                                 std::to_string(largest) + "; the CPU ray caster has no such limit");
    texture_3d(values_, GL_R32F, GL_RED, GL_FLOAT, dims_of(g), g.value.data(), true);
    check_gl("uploading the voxel values");
    // Normal xyz and gradient magnitude (shifted to a signed byte) together:
    // one fetch per sample.
    std::vector<int8_t> packed(4 * g.value.size());
    for (std::size_t v = 0; v < g.value.size(); ++v) {
        const raycast::Surface &s = g.surface[v];
        packed[4 * v] = s.normal[0];
        packed[4 * v + 1] = s.normal[1];
        packed[4 * v + 2] = s.normal[2];
        packed[4 * v + 3] = static_cast<int8_t>(static_cast<int>(s.gradient) - 128);
    }
    texture_3d(normals_, GL_RGBA8I, GL_RGBA_INTEGER, GL_BYTE, dims_of(g), packed.data());
    check_gl("uploading the normals");
}

void VolumeTextures::upload_labels(const raycast::VoxelGrid &g)
{
    labelled_ = !g.label.empty();
    resolvable_ = labelled_ && !g.tree.empty();
    if (!labelled_) {
        labels_.reset();
        tree_.reset();
        return;
    }
    // Each voxel's word: its label and whether its cell is mixed.
    if (g.max_label < 32768) {
        std::vector<uint16_t> small(g.label.size());
        for (std::size_t v = 0; v < small.size(); ++v)
            small[v] = static_cast<uint16_t>(g.label.word(v));
        texture_3d(labels_, GL_R16UI, GL_RED_INTEGER, GL_UNSIGNED_SHORT, dims_of(g), small.data());
    } else {
        std::vector<uint32_t> wide(g.label.size());
        for (std::size_t v = 0; v < wide.size(); ++v)
            wide[v] = g.label.word(v);
        texture_3d(labels_, GL_R32UI, GL_RED_INTEGER, GL_UNSIGNED_INT, dims_of(g), wide.data());
    }
    check_gl("uploading the label map");
    if (!resolvable_) {
        tree_.reset();
        return;
    }
    std::vector<float> tree(4 * static_cast<std::size_t>(g.tree.size()), 0.0f);
    for (uint32_t l = 0; l < g.tree.size(); ++l) {
        tree[4 * l] = static_cast<float>(g.tree.parent(l));
        tree[4 * l + 1] = static_cast<float>(g.tree.depth(l));
        tree[4 * l + 2] = g.tree.saddle(l);
    }
    texture_2d(tree_, GL_RGBA32F, static_cast<GLsizei>(g.tree.size()), 1, GL_RGBA, tree.data());
    check_gl("uploading the labels' tree");
}

void VolumeTextures::upload_blocks(const raycast::Occupancy &occupancy)
{
    texture_3d(blocks_, GL_R8UI, GL_RED_INTEGER, GL_UNSIGNED_BYTE, occupancy.blocks(), occupancy.flags().data());
    check_gl("uploading the empty blocks");
}

void VolumeTextures::upload_tables(const Tables &tables, const raycast::LocalOcclusion &occlusion,
                                   const raycast::BoundaryEmphasis &boundaries, const raycast::Shading &shading)
{
    const raycast::ClassTable &table = tables.full;
    GLint largest = 0;
    glGetIntegerv(GL_MAX_TEXTURE_SIZE, &largest);
    const GLsizei entries = static_cast<GLsizei>(table.entries()), labels = static_cast<GLsizei>(table.labels());
    if (entries > largest || labels > largest)
        throw std::runtime_error(std::to_string(labels) + " lookup tables of " + std::to_string(entries) +
                                 " entries exceed this OpenGL's texture size of " + std::to_string(largest));
    texture_2d(lut_, GL_RGBA32F, entries, labels, GL_RGBA, table.rgba().data());
    texture_2d(coarse_lut_, GL_RGBA32F, entries, labels, GL_RGBA, tables.coarse.rgba().data());
    texture_2d(refined_lut_, GL_RGBA32F, entries, labels, GL_RGBA, tables.full_refined.rgba().data());
    texture_2d(coarse_refined_lut_, GL_RGBA32F, entries, labels, GL_RGBA, tables.coarse_refined.rgba().data());
    // Unwritten when the occlusion is off (its tables are built only when on).
    const std::vector<float> &occluding = occlusion.table().rgba();
    texture_2d(occlusion_lut_, GL_RGBA32F, entries, labels, GL_RGBA,
               occluding.size() == table.rgba().size() ? occluding.data() : nullptr);
    std::vector<float> ranges(4 * static_cast<std::size_t>(labels));
    for (GLsizei l = 0; l < labels; ++l) {
        const auto &r = table.range(static_cast<uint32_t>(l));
        ranges[4 * l] = r.low;
        ranges[4 * l + 1] = r.scale;
        ranges[4 * l + 2] = r.last;
    }
    texture_2d(ranges_, GL_RGBA32F, labels, 1, GL_RGBA, ranges.data());
    std::vector<float> factors(2 * shading.highlight.size(), 1.0f);
    std::copy(boundaries.factors().begin(), boundaries.factors().end(), factors.begin());
    std::copy(shading.highlight.begin(), shading.highlight.end(), factors.begin() + shading.highlight.size());
    texture_2d(factors_, GL_R32F, static_cast<GLsizei>(shading.highlight.size()), 2, GL_RED, factors.data());
    check_gl("uploading the lookup tables");
}

void VolumeTextures::bind(bool coarse) const
{
    const auto at = [](unit::Unit u, GLenum target, const Texture &t) {
        glActiveTexture(GL_TEXTURE0 + static_cast<GLenum>(u));
        glBindTexture(target, t.get());
    };
    at(unit::values, GL_TEXTURE_3D, values_);
    at(unit::labels, GL_TEXTURE_3D, labels_);
    at(unit::normals, GL_TEXTURE_3D, normals_);
    at(unit::blocks, GL_TEXTURE_3D, blocks_);
    at(unit::lut, GL_TEXTURE_2D, coarse ? coarse_lut_ : lut_);
    at(unit::ranges, GL_TEXTURE_2D, ranges_);
    at(unit::factors, GL_TEXTURE_2D, factors_);
    at(unit::occlusion, GL_TEXTURE_2D, occlusion_lut_);
    at(unit::tree, GL_TEXTURE_2D, tree_);
    at(unit::refined, GL_TEXTURE_2D, coarse ? coarse_refined_lut_ : refined_lut_);
    glActiveTexture(GL_TEXTURE0);
}

} // namespace arbor::glraycast
