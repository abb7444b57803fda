#include "test_grids.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>
#include <openvdb/tools/Interpolation.h>
#include <nanovdb/util/OpenToNanoVDB.h>

#include "core/error.h"
#include "tools/vdb_writer.h"
#include "volume/nano_name_padding.h"

namespace mirage {

namespace {

[[noreturn]] void fail(const std::string& path, const std::string& msg) {
    throw MirageError(FileLoc{path}, msg);
}

// The index → object maps a test grid can carry, each stored as a different OpenVDB map type.
openvdb::math::Transform::Ptr makeTestTransform(const TestGridSpec& s, const std::string& path) {
    using namespace openvdb::math;
    const double h = s.voxelSize;
    const openvdb::Vec3d origin(s.origin.x, s.origin.y, s.origin.z);
    if (s.map == "uniform") return linearVdbTransform(h, s.origin);
    if (s.map == "scale")  // ScaleTranslateMap: voxels stretched ×2 along y
        return std::make_shared<Transform>(
            std::make_shared<ScaleTranslateMap>(openvdb::Vec3d(h, 2 * h, h), origin));
    if (s.map == "affine") {  // AffineMap: rotated 30° about z
        Mat4d m = Mat4d::identity();
        m.preScale(openvdb::Vec3d(h));
        m.postRotate(Z_AXIS, 0.5235987755982988);
        m.postTranslate(origin);
        return std::make_shared<Transform>(std::make_shared<AffineMap>(m));
    }
    if (s.map == "frustum")  // NonlinearFrustumMap over a 16³ index box
        return Transform::createFrustumTransform(
            openvdb::BBoxd(openvdb::Vec3d(0.0), openvdb::Vec3d(16.0)), 0.5, 2.0, h);
    fail(path, "test grid map '" + s.map + "' is not one of uniform, scale, affine, frustum");
}

template <typename GridT, typename MakeValue>
openvdb::GridBase::Ptr buildTestGrid(const TestGridSpec& s, typename GridT::ValueType background,
                                     MakeValue value) {
    typename GridT::Ptr grid = GridT::create(background);
    auto acc = grid->getAccessor();
    for (const auto& v : s.voxels)
        acc.setValue(openvdb::Coord(v.i, v.j, v.k), value(v.value, v.vector));
    for (const auto& v : s.inactiveVoxels)
        acc.setValueOff(openvdb::Coord(v.i, v.j, v.k), value(v.value, v.vector));
    for (const auto& t : s.tiles)
        grid->tree().addTile(openvdb::Index(t.level), openvdb::Coord(t.i, t.j, t.k),
                             value(t.value, Vec3d(t.value)), true);
    return grid;
}

}  // namespace

void writeTestGrids(const std::string& path, const std::vector<TestGridSpec>& specs,
                    const std::string& compression) {
    initOpenVdb();
    openvdb::GridPtrVec grids;
    for (const TestGridSpec& s : specs) {
        openvdb::GridBase::Ptr grid;
        if (s.valueType == "float") {
            grid = buildTestGrid<openvdb::FloatGrid>(
                s, float(s.background), [](double v, const Vec3d&) { return float(v); });
        } else if (s.valueType == "double") {
            grid = buildTestGrid<openvdb::DoubleGrid>(s, s.background,
                                                      [](double v, const Vec3d&) { return v; });
        } else if (s.valueType == "vec3s") {
            grid = buildTestGrid<openvdb::Vec3SGrid>(
                s, openvdb::Vec3s(float(s.background)), [](double, const Vec3d& v) {
                    return openvdb::Vec3s(float(v.x), float(v.y), float(v.z));
                });
        } else if (s.valueType == "bool") {
            grid = buildTestGrid<openvdb::BoolGrid>(
                s, s.background != 0.0, [](double v, const Vec3d&) { return v != 0.0; });
        } else if (s.valueType == "int32") {
            grid = buildTestGrid<openvdb::Int32Grid>(
                s, int32_t(s.background), [](double v, const Vec3d&) { return int32_t(v); });
        } else if (s.valueType == "int64") {
            grid = buildTestGrid<openvdb::Int64Grid>(
                s, int64_t(s.background), [](double v, const Vec3d&) { return int64_t(v); });
        } else if (s.valueType == "vec3d") {
            grid = buildTestGrid<openvdb::Vec3DGrid>(
                s, openvdb::Vec3d(s.background),
                [](double, const Vec3d& v) { return openvdb::Vec3d(v.x, v.y, v.z); });
        } else if (s.valueType == "vec3i") {
            grid = buildTestGrid<openvdb::Vec3IGrid>(
                s, openvdb::Vec3i(int(s.background)), [](double, const Vec3d& v) {
                    return openvdb::Vec3i(int(v.x), int(v.y), int(v.z));
                });
        } else if (s.valueType == "mask") {
            grid = buildTestGrid<openvdb::MaskGrid>(s, false,
                                                    [](double v, const Vec3d&) { return v != 0.0; });
        } else {
            fail(path, "test grid type '" + s.valueType +
                           "' is not one of float, double, vec3s, bool, int32, int64, vec3d, "
                           "vec3i, mask");
        }
        if (s.shareTreeWithPrevious) {
            if (grids.empty() || grids.back()->type() != grid->type())
                fail(path, "test grid '" + s.name + "' shares the tree of a previous grid of "
                                                    "another type, or of none");
            grid->setTree(grids.back()->baseTreePtr());
        }
        openvdb::GridClass cls = openvdb::GridBase::stringToGridClass(s.gridClass);
        if (cls == openvdb::GRID_UNKNOWN && s.gridClass != "unknown")
            fail(path, "test grid class '" + s.gridClass +
                           "' is not one of fog volume, level "
                           "set, staggered, unknown");
        grid->setGridClass(cls);
        grid->setName(s.name);
        grid->setTransform(makeTestTransform(s, path));
        grid->setSaveFloatAsHalf(s.saveAsHalf);
        grids.push_back(grid);
    }
    writeVdbFile(path, grids, openvdb::MetaMap(), compression);
}

std::vector<double> openvdbSampleForTest(const std::string& path, const std::string& gridName,
                                         const std::vector<Vec3d>& points, bool indexSpace) {
    initOpenVdb();
    openvdb::io::File file(path);
    file.open();
    openvdb::FloatGrid::Ptr grid = openvdb::gridPtrCast<openvdb::FloatGrid>(file.readGrid(gridName));
    file.close();
    if (!grid) fail(path, "grid '" + gridName + "' is not a float grid");
    std::vector<double> values;
    values.reserve(points.size());
    openvdb::tools::GridSampler<openvdb::FloatGrid, openvdb::tools::BoxSampler> sampler(*grid);
    for (const Vec3d& p : points) {
        openvdb::Vec3d q(p.x, p.y, p.z);
        values.push_back(indexSpace ? sampler.isSample(q) : sampler.wsSample(q));
    }
    return values;
}

std::string eagerNanoVdbForTest(const std::string& path, const std::string& gridName) {
    initOpenVdb();
    openvdb::io::File file(path);
    file.open(/*delayLoad=*/false);
    openvdb::GridBase::Ptr base = file.readGrid(gridName);
    file.close();
    nanovdb::GridHandle<nanovdb::HostBuffer> handle;
    if (auto scalar = openvdb::gridPtrCast<openvdb::FloatGrid>(base))
        handle = nanovdb::openToNanoVDB(*scalar, nanovdb::StatsMode::All,
                                        nanovdb::ChecksumMode::Partial);
    else if (auto vector = openvdb::gridPtrCast<openvdb::Vec3SGrid>(base))
        handle = nanovdb::openToNanoVDB(*vector, nanovdb::StatsMode::All,
                                        nanovdb::ChecksumMode::Partial);
    else
        fail(path, "grid '" + gridName + "' is neither a float nor a vec3s grid");
    zeroNamePadding(handle);  // as the loader does: the same bytes every time
    return std::string(reinterpret_cast<const char*>(handle.data()), handle.size());
}

}  // namespace mirage
