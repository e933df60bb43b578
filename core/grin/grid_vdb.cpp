// Sampled gradient-index fields from and to OpenVDB files (core/grin/grid.h): the one file of
// refract that includes OpenVDB's headers.
#include <refract/core/grin/grid.h>

#include <cmath>
#include <filesystem>
#include <mutex>
#include <sstream>

#include <openvdb/io/Stream.h>
#include <openvdb/openvdb.h>

#include <refract/geometry/atomic_file.h>
#include <refract/geometry/error.h>
#include <refract/geometry/format.h>

namespace refract::grin {

namespace {

void initialise() {
    static std::once_flag once;
    std::call_once(once, [] { openvdb::initialize(); });
}

// The dense samples of a scalar grid over its active voxels' bounding box.
template <typename GridT>
GridSamples dense(const GridT& grid, const std::string& where) {
    const openvdb::CoordBBox box = grid.evalActiveVoxelBoundingBox();
    if (box.empty()) throw InputError(where + "/grid: '" + clip_echo(grid.getName()) + "' has no active voxels");
    const openvdb::math::Transform& t = grid.transform();
    if (!t.isLinear()) throw InputError(where + "/file: the grid's voxel transform is not linear (frustum)");
    // A linear transform without rotation or shear: index (i, j, k) ↦ origin + (i, j, k)·voxel size.
    const openvdb::Mat4d m = t.baseMap()->getAffineMap()->getMat4();
    for (int r = 0; r < 3; ++r)
        for (int c = 0; c < 3; ++c)
            if (r != c && std::abs(m(r, c)) > 1e-12 * std::abs(m(r, r)))
                throw InputError(where + "/file: the grid's voxel transform rotates or shears (only a scale and a "
                                         "translation are supported)");
    const openvdb::Vec3d lo = t.indexToWorld(box.min());
    const openvdb::Vec3d step = t.voxelSize();
    GridSamples s;
    const openvdb::Coord dim = box.dim();
    check_grid_size(dim.x(), dim.y(), dim.z(), where + "/file");
    s.dims = {dim.x(), dim.y(), dim.z()};
    s.origin = Vec3(lo.x(), lo.y(), lo.z());
    s.spacing = Vec3(step.x(), step.y(), step.z());
    s.values.resize(static_cast<size_t>(dim.x()) * static_cast<size_t>(dim.y()) * static_cast<size_t>(dim.z()));
    auto acc = grid.getConstAccessor();
    size_t n = 0;
    for (int k = 0; k < dim.z(); ++k)
        for (int j = 0; j < dim.y(); ++j)
            for (int i = 0; i < dim.x(); ++i)
                s.values[n++] = static_cast<double>(acc.getValue(box.min().offsetBy(i, j, k)));
    return s;
}

}  // namespace

GridSamples read_vdb_grid(const std::string& path, const std::string& grid_name, const std::string& where) {
    initialise();
    if (!std::filesystem::is_regular_file(path))
        throw InputError(where + "/file: no such file '" + clip_echo(path) + "'");
    openvdb::GridBase::Ptr base;
    std::string names;
    try {
        openvdb::io::File f(path);
        f.open(false);  // no delayed loading: the file is read once
        for (auto it = f.beginName(); it != f.endName(); ++it) {
            const std::string n = it.gridName();
            names += (names.empty() ? "" : ", ") + n;
            if (!base && (grid_name.empty() ? true : n == grid_name)) {
                openvdb::GridBase::Ptr g = f.readGrid(n);
                if (grid_name.empty() && !g->isType<openvdb::FloatGrid>() && !g->isType<openvdb::DoubleGrid>())
                    continue;  // the first scalar grid
                base = g;
            }
        }
        f.close();
    } catch (const openvdb::Exception& e) {
        throw InputError(where + "/file: cannot read '" + clip_echo(path) + "' as an OpenVDB file (" + e.what() + ")");
    }
    if (!base) {
        if (grid_name.empty()) throw InputError(where + "/file: '" + clip_echo(path) + "' holds no float grid");
        throw InputError(where + "/grid: no grid '" + clip_echo(grid_name) + "' in '" + clip_echo(path) + "' (" +
                         (names.empty() ? std::string("none") : clip_echo(names)) + ")");
    }
    if (auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(base)) return dense(*f, where);
    if (auto d = openvdb::gridPtrCast<openvdb::DoubleGrid>(base)) return dense(*d, where);
    throw InputError(where + "/grid: '" + clip_echo(base->getName()) + "' is a " + base->valueType() +
                     " grid, a float or double grid is needed");
}

namespace {

template <typename GridT>
typename GridT::Ptr filled_grid(const std::string& grid_name, const GridSamples& s) {
    using V = typename GridT::ValueType;
    typename GridT::Ptr g = GridT::create(V(0));
    g->setName(grid_name);
    openvdb::math::Transform::Ptr t = openvdb::math::Transform::createLinearTransform(s.spacing.x());
    t->postTranslate(openvdb::Vec3d(s.origin.x(), s.origin.y(), s.origin.z()));
    g->setTransform(t);
    auto acc = g->getAccessor();
    size_t n = 0;
    for (int k = 0; k < s.dims[2]; ++k)
        for (int j = 0; j < s.dims[1]; ++j)
            for (int i = 0; i < s.dims[0]; ++i) acc.setValueOn(openvdb::Coord(i, j, k), static_cast<V>(s.values[n++]));
    return g;
}

}  // namespace

void write_vdb_grid(const std::string& path, const std::string& grid_name, const GridSamples& s, VdbPrecision precision) {
    initialise();
    const auto fail = [&](const std::string& why) { throw InputError(path + ": " + why); };
    if (grid_name.empty()) fail("the grid needs a name");
    for (int a = 0; a < 3; ++a)
        if (s.dims[a] < 1) fail("the grid needs at least one sample along each axis");
    const size_t count = size_t(s.dims[0]) * size_t(s.dims[1]) * size_t(s.dims[2]);
    if (s.values.size() != count)
        fail(std::to_string(s.values.size()) + " values for " + std::to_string(count) + " samples");
    if (!(s.spacing.x() > 0 && std::isfinite(s.spacing.x()) && s.origin.allFinite()))
        fail("the spacing must be finite and > 0 and the origin finite");
    if (!(std::abs(s.spacing.x() - s.spacing.y()) <= 1e-12 * s.spacing.x() &&
          std::abs(s.spacing.x() - s.spacing.z()) <= 1e-12 * s.spacing.x()))
        fail("an OpenVDB grid has one voxel size: the spacing must be the same along x, y and z");
    for (size_t n = 0; n < count; ++n)
        if (!std::isfinite(s.values[n])) fail("sample " + std::to_string(n) + " is " + format_value(s.values[n]));
    openvdb::GridPtrVec grids;
    if (precision == VdbPrecision::double_)
        grids.push_back(filled_grid<openvdb::DoubleGrid>(grid_name, s));
    else
        grids.push_back(filled_grid<openvdb::FloatGrid>(grid_name, s));
    std::ostringstream bytes(std::ios::binary);
    openvdb::io::Stream(bytes).write(grids);
    write_file_atomic(path, bytes.str());
}

}  // namespace refract::grin
