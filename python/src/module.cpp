// svo's Python module: numpy arrays in; grids (pyopenvdb's where it imports,
// else svo.Grid) and numpy arrays out, as svo.Result.
// Parses, calls the library (svo/svo.h) and converts; the work is the library's.
#include <boost/python.hpp>
#include <openvdb/io/Stream.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>
#include <pybind11/stl/filesystem.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "svo/gl/context.h"
#include "svo/gl/octree_view.h"
#include "svo/gl/view_request.h"
#include "svo/core/region.h"
#include "svo/vdb_io/join_region.h"
#include "svo/vdb_io/nanovdb_file.h"
#include "svo/vdb_io/vdb_file.h"
#include "svo/result_metadata.h"
#include "svo/svo.h"
#ifdef SVO_WITH_VALIDATE
#include "svo/validate/level_set_report.h"
#include "svo/validate/report.h"
#endif

namespace py = pybind11;
namespace bp = boost::python;

namespace {

// --- errors --------------------------------------------------------------

/// Bad arguments: ValueError. Raised before any GPU work.
[[noreturn]] void badValue(const std::string& what) { throw py::value_error(what); }

// The library's errors become Python's by their type alone (one translator,
// registered in PYBIND11_MODULE below): svo::InvalidInput -> ValueError,
// svo::IoError -> OSError, svo::DeviceError -> RuntimeError,
// svo::OutOfMemory -> svo.OutOfMemoryError (a MemoryError, and a
// RuntimeError as GPU memory errors were before), svo::Unsupported ->
// NotImplementedError (a RuntimeError), svo::Interrupted -> KeyboardInterrupt.
// Where the module checks a keyword with a library rule (svo::checkBand, ...),
// the rule names the keyword; where the library names an option by its
// identifier ("VoxelizeOptions::dilation"), the message names the keyword
// that sets it instead (pythonMessage).

// --- grids between OpenVDB and Python ----------------------------------------
//
// Where python3-openvdb (pyopenvdb) imports, grids cross as the very objects it
// makes: it registers Boost.Python converters for OpenVDB's grid pointers, and
// this module, linked against the same libopenvdb, uses them. Where it does
// not (another CPython, a venv without system site packages), grids come as
// svo.Grid, this module's own small grid type (PyGrid); Grid.to_pyopenvdb()
// converts later where it can.

/// Whether pyopenvdb imports in this interpreter: asked once, at the module's
/// import (svo/__init__.py imports pyopenvdb first where it can).
bool havePyopenvdb()
{
    static const bool have = [] {
        try {
            py::module_::import("pyopenvdb");
            return true;
        } catch (py::error_already_set&) { // ImportError, or a pyopenvdb that fails to load
            return false;
        }
    }();
    return have;
}

/// svo.Grid: one OpenVDB grid, shared with nobody else.
struct PyGrid {
    openvdb::GridBase::Ptr grid;
};

/// The grid types pyopenvdb has (python3-openvdb 10: no MaskGrid, no Int32Grid).
bool pyopenvdbHas(const openvdb::GridBase& grid)
{
    return grid.isType<openvdb::BoolGrid>() || grid.isType<openvdb::FloatGrid>() || grid.isType<openvdb::Vec3SGrid>();
}

/// @a grid as a pyopenvdb grid (sharing it). The caller checked havePyopenvdb() and pyopenvdbHas().
py::object toPyopenvdb(const openvdb::GridBase::Ptr& grid)
{
    bp::object o;
    if (auto g = openvdb::gridPtrCast<openvdb::BoolGrid>(grid)) o = bp::object(g);
    else if (auto f = openvdb::gridPtrCast<openvdb::FloatGrid>(grid)) o = bp::object(f);
    else if (auto v = openvdb::gridPtrCast<openvdb::Vec3SGrid>(grid)) o = bp::object(v);
    return py::reinterpret_borrow<py::object>(o.ptr());
}

/// A result grid as Python gets it: pyopenvdb's where it imports and has the type, else svo.Grid.
py::object toPython(const openvdb::GridBase::Ptr& grid)
{
    if (havePyopenvdb() && pyopenvdbHas(*grid)) return toPyopenvdb(grid);
    return py::cast(PyGrid{grid});
}

/// An svo.Grid or a pyopenvdb grid (BoolGrid, FloatGrid, Vec3SGrid) as OpenVDB's, or null.
openvdb::GridBase::Ptr fromPython(const py::handle& obj)
{
    if (py::isinstance<PyGrid>(obj)) return obj.cast<const PyGrid&>().grid;
    if (!havePyopenvdb()) return nullptr;
    const bp::object o{bp::handle<>(bp::borrowed(obj.ptr()))};
    if (bp::extract<openvdb::BoolGrid::Ptr> b(o); b.check()) return b();
    if (bp::extract<openvdb::FloatGrid::Ptr> f(o); f.check()) return f();
    if (bp::extract<openvdb::Vec3SGrid::Ptr> v(o); v.check()) return v();
    return nullptr;
}

/// fromPython, or a ValueError naming @a what.
openvdb::GridBase::Ptr gridArgument(const py::handle& obj, const std::string& what)
{
    const openvdb::GridBase::Ptr grid = fromPython(obj);
    if (!grid) badValue(what + ": expected an svo.Grid or a pyopenvdb BoolGrid, FloatGrid or Vec3SGrid");
    return grid;
}

// --- svo.Grid -------------------------------------------------------------------

/// The grid types svo.Grid reads values of: every type a result has.
using GridTypes = openvdb::TypeList<openvdb::BoolGrid, openvdb::FloatGrid, openvdb::Vec3SGrid, openvdb::Int32Grid,
                                    openvdb::MaskGrid>;

/// A grid's value as Python's: bool, float, int or (x, y, z).
template <typename T>
py::object valueObject(const T& v)
{
    if constexpr (openvdb::VecTraits<T>::IsVec) return py::make_tuple(v[0], v[1], v[2]);
    else if constexpr (std::is_same_v<T, openvdb::ValueMask>) return py::bool_(false); // a mask's background: off
    else return py::cast(v);
}

/// Grid.ijk and Grid.values: the active voxels (tiles expanded) in OpenVDB's
/// tree order, (K, 3) int32, and their values, (K,) or (K, 3) of the grid's type.
std::pair<py::array, py::array> activeArrays(const openvdb::GridBase& base)
{
    std::pair<py::array, py::array> out;
    base.apply<GridTypes>([&](const auto& grid) {
        using GridT = std::decay_t<decltype(grid)>;
        using V = typename GridT::ValueType;
        constexpr bool isVec = openvdb::VecTraits<V>::IsVec;
        using Element = std::conditional_t<isVec, float, std::conditional_t<std::is_same_v<V, openvdb::ValueMask>, bool, V>>;
        std::vector<int32_t> ijk;
        std::vector<Element> values;
        {
            py::gil_scoped_release release;
            ijk.reserve(3 * grid.activeVoxelCount());
            for (auto it = grid.tree().cbeginValueOn(); it; ++it) {
                openvdb::CoordBBox box;
                it.getBoundingBox(box); // one voxel, or a whole active tile
                for (auto c = box.begin(); c; ++c) {
                    ijk.insert(ijk.end(), {(*c).x(), (*c).y(), (*c).z()});
                    if constexpr (isVec) values.insert(values.end(), {(*it)[0], (*it)[1], (*it)[2]});
                    else if constexpr (std::is_same_v<V, openvdb::ValueMask>) values.push_back(true);
                    else values.push_back(*it);
                }
            }
        }
        const auto k = py::ssize_t(ijk.size() / 3);
        py::array_t<int32_t> coords({k, py::ssize_t(3)});
        std::copy(ijk.begin(), ijk.end(), coords.mutable_data());
        py::array_t<Element> vals = isVec ? py::array_t<Element>({k, py::ssize_t(3)}) : py::array_t<Element>(k);
        std::copy(values.begin(), values.end(), vals.mutable_data());
        out = {coords, vals};
    });
    return out;
}

/// The grid's index-to-world matrix, 4x4, in OpenVDB's row-vector convention (the transform= keyword's).
py::array_t<double> transformMatrix(const openvdb::GridBase& grid)
{
    const auto map = grid.transform().baseMap();
    if (!map->isLinear()) badValue("transform: grid '" + grid.getName() + "' has a non-linear transform");
    const openvdb::Mat4d m = map->getAffineMap()->getMat4();
    py::array_t<double> out({4, 4});
    auto w = out.mutable_unchecked<2>();
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) w(i, j) = m(i, j);
    return out;
}

/// Grids to one file, the format by the extension (.vdb or .nvdb), with the
/// library's writers (atomic); @a codec names a .nvdb file's NanoVDB codec.
void writeGrids(const std::filesystem::path& path, const openvdb::GridPtrVec& grids, const std::string& codec)
{
    const std::string file = path.string();
    const svo::OutputFormat format = svo::outputFormat(file); // svo::IoError for another extension: OSError
    if (format == svo::OutputFormat::Svo)
        badValue(file + ": a .svo file holds an octree; write grids as .vdb or .nvdb (Octree.save writes .svo)");
    const auto nanoCodec = svo::parse<svo::vdb::NanoCodec>(codec, "codec"); // InvalidInput: ValueError
    if (format == svo::OutputFormat::Vdb && nanoCodec != svo::vdb::NanoCodec::None)
        badValue(file + ": codec applies to .nvdb files; a .vdb file is compressed by OpenVDB's own settings");
    py::gil_scoped_release release;
    if (format == svo::OutputFormat::NanoVdb) svo::vdb::writeNanoVdb(file, grids, nanoCodec);
    else svo::vdb::writeVdbGrids(file, grids, {}); // each grid's metadata is already on it
}

/// svo.write(path, grids): svo.Grid or pyopenvdb grids, in one file.
void writeAny(const std::filesystem::path& path, const py::iterable& list, const std::string& codec)
{
    openvdb::GridPtrVec grids;
    for (const py::handle& item : list) grids.push_back(gridArgument(item, "grids"));
    if (grids.empty()) badValue("grids: no grid to write");
    writeGrids(path, grids, codec);
}

/// Appends what is written to a string (std::ostringstream grows by copies,
/// then copies again to give its string: 0.1 s of a 71 MB level set's 0.3 s).
struct StringSink : std::streambuf {
    std::string out;
    std::streamsize xsputn(const char* s, std::streamsize n) override
    {
        out.append(s, std::size_t(n));
        return n;
    }
    int_type overflow(int_type c) override
    {
        if (!traits_type::eq_int_type(c, traits_type::eof())) out.push_back(traits_type::to_char_type(c));
        return traits_type::not_eof(c);
    }
};

/// The grid as bytes of an OpenVDB stream, for pickling and for svo.distributed's
/// tiles (Dask sends them between processes). Only the active-mask compression:
/// the bytes cross a socket, not a disk, and OpenVDB's default (Blosc at its
/// highest level) made the round trip of a 66 MB level set 0.7 s.
std::string gridBytes(const openvdb::GridBase::Ptr& grid)
{
    py::gil_scoped_release release;
    StringSink sink;
    sink.out.reserve(std::size_t(grid->memUsage())); // the stream is smaller; pages are touched as written
    std::ostream os(&sink);
    openvdb::io::Stream stream(os);
    stream.setCompression(openvdb::io::COMPRESS_ACTIVE_MASK);
    stream.write(openvdb::GridCPtrVec{grid});
    return std::move(sink.out);
}

/// gridBytes as a uint8 numpy array that owns them (no copy into a bytes
/// object; Dask sends arrays without pickling them).
py::array gridArray(const openvdb::GridBase::Ptr& grid)
{
    auto* bytes = new std::string(gridBytes(grid));
    py::capsule owner(bytes, [](void* p) { delete static_cast<std::string*>(p); });
    return py::array_t<std::uint8_t>(py::ssize_t(bytes->size()), reinterpret_cast<const std::uint8_t*>(bytes->data()),
                                     owner);
}

/// Reads bytes in place (no copy into a string stream).
struct BytesBuffer : std::streambuf {
    BytesBuffer(const char* data, std::size_t size)
    {
        char* p = const_cast<char*>(data); // read only: std::streambuf's get area is char*
        setg(p, p, p + size);
    }
};

/// The grid of gridBytes' bytes (bytes, or any contiguous buffer: gridArray's).
/// @throw ValueError when they hold no single grid.
openvdb::GridBase::Ptr gridFromBytes(const py::buffer& bytes)
{
    const py::buffer_info info = bytes.request();
    if (info.ndim != 1 || info.strides[0] != info.itemsize) badValue("svo.Grid: expected contiguous bytes");
    openvdb::GridPtrVecPtr grids;
    try {
        py::gil_scoped_release release;
        BytesBuffer buffer(static_cast<const char*>(info.ptr), std::size_t(info.size * info.itemsize));
        std::istream is(&buffer);
        // Not delayed: a delayed-loading stream copies itself to a temporary
        // file and reads each leaf from there on its first touch.
        grids = openvdb::io::Stream(is, /*delayLoad=*/false).getGrids();
    } catch (const openvdb::Exception& e) {
        badValue(std::string("svo.Grid: the bytes hold no OpenVDB grid (") + e.what() + ")");
    }
    if (!grids || grids->size() != 1) badValue("svo.Grid: the bytes hold no single grid");
    return grids->front();
}

void bindGrid(py::module_& m)
{
    py::class_<PyGrid>(m, "Grid",
                       "A grid svo made, where python3-openvdb (pyopenvdb) does not import or lacks its type: its "
                       "name, class, transform, active voxels and values as numpy arrays, and metadata; write() "
                       "stores it as .vdb or .nvdb, to_pyopenvdb() converts it where pyopenvdb imports.")
        .def_property("name", [](const PyGrid& g) { return g.grid->getName(); },
                      [](PyGrid& g, const std::string& name) { g.grid->setName(name); }, "The grid's name.")
        .def_property_readonly("type", [](const PyGrid& g) { return g.grid->valueType(); },
                               "The value type: 'bool', 'float', 'vec3s', 'int32' or 'mask'.")
        .def_property_readonly("grid_class",
                               [](const PyGrid& g) { return openvdb::GridBase::gridClassToString(g.grid->getGridClass()); },
                               "OpenVDB's grid class: 'level set', 'fog volume' or 'unknown'.")
        .def_property_readonly("transform", [](const PyGrid& g) { return transformMatrix(*g.grid); },
                               "Index to world, a 4x4 matrix in OpenVDB's row-vector convention (world = [i j k 1] @ "
                               "M), as the transform= keyword takes it.")
        .def_property_readonly("voxel_size", [](const PyGrid& g) {
            const openvdb::Vec3d v = g.grid->voxelSize();
            return py::make_tuple(v[0], v[1], v[2]);
        }, "World units per voxel along x, y, z.")
        .def_property_readonly("background", [](const PyGrid& g) {
            py::object out;
            g.grid->apply<GridTypes>([&](const auto& grid) { out = valueObject(grid.background()); });
            return out;
        }, "The value of inactive voxels outside the active ones.")
        .def_property_readonly("active_voxel_count", [](const PyGrid& g) { return g.grid->activeVoxelCount(); })
        .def_property_readonly("ijk", [](const PyGrid& g) { return activeArrays(*g.grid).first; },
                               "(K, 3) int32 index coordinates of the active voxels (tiles expanded), in OpenVDB's "
                               "tree order. Made on each access.")
        .def_property_readonly("values", [](const PyGrid& g) { return activeArrays(*g.grid).second; },
                               "The active voxels' values in the order of ijk: (K,) bool, float32 or int32, or (K, 3) "
                               "float32. Made on each access.")
        .def_property_readonly("metadata", [](const PyGrid& g) {
            py::dict out;
            for (auto meta = g.grid->beginMeta(); meta != g.grid->endMeta(); ++meta)
                out[py::str(meta->first)] = meta->second->str();
            return out;
        }, "The grid's metadata, each value as text (svo:source, svo:version, svo:sign, ...).")
        .def("write",
             [](const PyGrid& g, const std::filesystem::path& path, const std::string& codec) {
                 writeGrids(path, {g.grid}, codec);
             },
             py::arg("path"), py::kw_only(), py::arg("codec") = "none",
             "Write the grid to a .vdb or .nvdb file (svo's writers: a temporary file renamed into place); codec: "
             "a .nvdb file's NanoVDB codec, 'none', 'zip' or 'blosc'.")
        .def("to_pyopenvdb", [](const PyGrid& g) {
            if (!havePyopenvdb())
                throw py::import_error("svo.Grid.to_pyopenvdb: pyopenvdb does not import in this interpreter (" +
                                       py::cast<std::string>(py::module_::import("sys").attr("executable")) +
                                       "); Debian's python3-openvdb serves /usr/bin/python3");
            if (!pyopenvdbHas(*g.grid))
                throw py::type_error("svo.Grid.to_pyopenvdb: pyopenvdb has no " + g.grid->valueType() +
                                     " grid type; write() the grid to a file instead");
            return toPyopenvdb(g.grid->deepCopyGrid());
        }, "A pyopenvdb grid with the same voxels, values, transform and metadata (a copy).")
        .def("__repr__", [](const PyGrid& g) {
            return "<svo.Grid '" + g.grid->getName() + "': " + g.grid->valueType() + ", " +
                   std::to_string(g.grid->activeVoxelCount()) + " active voxels>";
        })
        .def(py::pickle([](const PyGrid& g) { return py::bytes(gridBytes(g.grid)); },
                        [](const py::bytes& b) { return PyGrid{gridFromBytes(b)}; }));
    m.def("write", &writeAny, py::arg("path"), py::arg("grids"), py::kw_only(), py::arg("codec") = "none",
          "Write grids (svo.Grid or pyopenvdb grids) to one .vdb or .nvdb file with svo's writers, atomically; codec: "
          "a .nvdb file's NanoVDB codec, 'none', 'zip' or 'blosc'.");
}

// --- joining regions (svo.distributed) --------------------------------------

void joinRegion(const py::handle& intoObj, const py::handle& partObj)
{
    const openvdb::GridBase::Ptr into = gridArgument(intoObj, "into"), part = gridArgument(partObj, "part");
    svo::vdb::joinRegion(*into, *part);
}

// --- arrays ----------------------------------------------------------------

/// The shape of an array as Python writes it: "(1, 2)".
std::string shapeText(const py::array& a)
{
    return std::string(py::str(py::tuple(py::cast(std::vector<py::ssize_t>(a.shape(), a.shape() + a.ndim())))));
}

/// (N, 3) float64 vertices from anything numpy takes; checked for shape and finiteness.
std::vector<openvdb::Vec3d> toPoints(const py::handle& obj)
{
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
    if (!a) badValue("vertices: expected an (N, 3) array of numbers");
    if (a.ndim() != 2 || a.shape(1) != 3)
        badValue("vertices: expected shape (N, 3), got " + shapeText(a));
    if (a.shape(0) == 0) badValue("vertices: the array is empty");
    const auto r = a.unchecked<2>();
    std::vector<openvdb::Vec3d> out(size_t(a.shape(0)));
    for (py::ssize_t i = 0; i < a.shape(0); ++i) {
        out[size_t(i)] = openvdb::Vec3d(r(i, 0), r(i, 1), r(i, 2));
        if (!std::isfinite(r(i, 0)) || !std::isfinite(r(i, 1)) || !std::isfinite(r(i, 2)))
            badValue("vertices: row " + std::to_string(i) + " is not finite (NaN or Inf)");
    }
    return out;
}

/// (M, 3) triangles or (M, 4) quads of non-negative indices below `vertices`.
/// Unsigned arrays are read as unsigned, so that an index past 2^63 is named
/// as it is, not wrapped to a negative number.
void toFaces(const py::handle& obj, size_t vertices, std::vector<openvdb::Vec3I>& triangles,
             std::vector<openvdb::Vec4I>& quads)
{
    const py::array raw = py::array::ensure(obj);
    if (raw && raw.dtype().kind() == 'f') badValue("triangles: expected integers, got a floating-point array");
    const bool isUnsigned = raw && raw.dtype().kind() == 'u';
    const auto u = isUnsigned ? py::array_t<uint64_t, py::array::c_style | py::array::forcecast>::ensure(obj)
                              : py::array_t<uint64_t, py::array::c_style | py::array::forcecast>();
    const auto a = isUnsigned ? py::array_t<int64_t, py::array::c_style | py::array::forcecast>()
                              : py::array_t<int64_t, py::array::c_style | py::array::forcecast>::ensure(obj);
    const py::array& any = isUnsigned ? static_cast<const py::array&>(u) : static_cast<const py::array&>(a);
    if (!any) badValue("triangles: expected an (M, 3) or (M, 4) array of integers");
    if (any.ndim() != 2 || (any.shape(1) != 3 && any.shape(1) != 4))
        badValue("triangles: expected shape (M, 3) or (M, 4), got " + shapeText(any));
    if (any.shape(0) == 0) badValue("triangles: the array is empty");
    const py::ssize_t rows = any.shape(0), cols = any.shape(1);
    // Index (i, c) as written: non-negative ones as uint64, negative ones as int64.
    auto bad = [&](py::ssize_t i, const std::string& index) {
        badValue("triangles: row " + std::to_string(i) + " refers to vertex " + index + ", but there are " +
                 std::to_string(vertices) + " vertices");
    };
    std::vector<uint32_t> flat(size_t(rows * cols));
    if (isUnsigned) {
        const auto r = u.unchecked<2>();
        for (py::ssize_t i = 0; i < rows; ++i)
            for (py::ssize_t c = 0; c < cols; ++c) {
                if (r(i, c) >= vertices) bad(i, std::to_string(r(i, c)));
                flat[size_t(i * cols + c)] = uint32_t(r(i, c));
            }
    } else {
        const auto r = a.unchecked<2>();
        for (py::ssize_t i = 0; i < rows; ++i)
            for (py::ssize_t c = 0; c < cols; ++c) {
                if (r(i, c) < 0 || uint64_t(r(i, c)) >= vertices) bad(i, std::to_string(r(i, c)));
                flat[size_t(i * cols + c)] = uint32_t(r(i, c));
            }
    }
    for (py::ssize_t i = 0; i < rows; ++i) {
        const uint32_t* f = &flat[size_t(i * cols)];
        if (cols == 3) triangles.emplace_back(f[0], f[1], f[2]);
        else quads.emplace_back(f[0], f[1], f[2], f[3]);
    }
}

/// A pyopenvdb Transform, or a 4x4 matrix in OpenVDB's row-vector
/// convention (world = [i j k 1] @ M, translation in the last row).
openvdb::math::Transform::Ptr toTransform(const py::handle& obj)
{
    if (havePyopenvdb()) {
        const bp::object o{bp::handle<>(bp::borrowed(obj.ptr()))};
        if (bp::extract<openvdb::math::Transform::Ptr> t(o); t.check()) return t()->copy();
    }
    const auto a = py::array_t<double, py::array::c_style | py::array::forcecast>::ensure(obj);
    if (!a || a.ndim() != 2 || a.shape(0) != 4 || a.shape(1) != 4)
        badValue("transform: expected a pyopenvdb.Transform or a 4x4 matrix");
    const auto r = a.unchecked<2>();
    openvdb::Mat4d m;
    for (int i = 0; i < 4; ++i)
        for (int j = 0; j < 4; ++j) {
            if (!std::isfinite(r(i, j))) badValue("transform: the matrix has a NaN or Inf entry");
            m(i, j) = r(i, j);
        }
    if (m(0, 3) != 0 || m(1, 3) != 0 || m(2, 3) != 0 || m(3, 3) != 1)
        badValue("transform: not affine; its last column must be (0, 0, 0, 1) (OpenVDB's row-vector convention)");
    if (std::abs(m.getMat3().det()) < 1e-300) badValue("transform: the matrix is singular");
    return openvdb::math::Transform::createLinearTransform(m);
}

// --- keywords ----------------------------------------------------------------
//
// Each keyword is declared once: the library's options beside their structs
// (forEachOption, svo/core/option_info.h), Python's own ones in
// kPythonKeywords. A call lists the keywords it takes (kCalls); reading its
// **kwargs, its docstring and svo._options() (which the stub's test reads)
// all come from those declarations, so none of them can drift apart.

/// A keyword only Python has: no library struct declares it.
struct PythonKeyword {
    std::string_view keyword;
    py::object (*fallback)(); ///< its default; a function, as no Python object exists before the module loads
    std::string_view doc;
};

py::object none() { return py::none(); }

const PythonKeyword kPythonKeywords[] = {
    {"transform", none,
     "A pyopenvdb.Transform or a 4x4 affine matrix (OpenVDB's row-vector convention), instead of resolution; "
     "voxels are cubes of its index space"},
    {"grid", [] { return py::object(py::str("bool")); },
     "'bool' (a BoolGrid 'surface', true on voxels) or 'fog' (a FloatGrid 'density', 1 on voxels)"},
    {"kind", [] { return py::object(py::str("surface")); },
     "What write_nanovdb() lays out: 'surface' (voxelize()), 'sdf' (level_set()), 'udf' (level_set(unsigned=True)), "
     "'solid' (solid()) or 'band' (the voxels nearer than exterior_band to a triangle: the active voxels of 'udf', "
     "as a topology grid 'band')"},
    {"report", [] { return py::object(py::bool_(false)); },
     "Also say what the call did, as Result.report: backend, mode, sign method, voxels, GPU memory, stage times"},
    // Octree.render's own: what svo view takes in other forms (--size WxH, --layers a,b, --levels a:b,
    // --light sun:..., colours as r,g,b) or under other names (--render for lighting and ao_only).
    {"size", [] { return py::object(py::make_tuple(640, 480)); }, "(width, height) of the picture, 1 to 16384 pixels each"},
    {"view", [] { return py::object(py::str("front")); },
     "'front' or an axis view '+x', '-x', '+y', '-y', '+z', '-z' (orthographic), framing the octree's grid"},
    {"layers", [] { return py::object(py::make_tuple("voxels", "outlines")); },
     "The layers drawn: 'voxels', 'outlines', 'bricks'"},
    {"levels", none, "(first, last) outline levels, 0 = root (None: all)"},
    {"ao_only", [] { return py::object(py::bool_(false)); },
     "The voxels as their ambient occlusion alone, grey (5 cones unless ao says), as svo view --render ao"},
    {"lighting", [] { return py::object(py::str("off")); },
     "'off', 'direct' (direct light with shadows) or 'gi' (and one diffuse bounce), as svo view --render direct or "
     "gi; needs the normal channel"},
    {"lights", none,
     "[('sun', (dx, dy, dz)[, E]), ('point', (x, y, z)[, I]), ...] in world units, E and I a number or (r, g, b), "
     "pi by default (None: a sun from above-left-front)"},
    {"albedo", none,
     "Lit pictures: the surface albedo, a number or (r, g, b) in [0, 1], where the octree has no colour channel "
     "(None: 0.75)"},
    {"specular", none,
     "lighting='gi': glossy reflectance, a number or (r, g, b) in [0, 1]: one more cone along the mirrored view ray "
     "(None: 0, none)"},
    {"mesh", none,
     "(vertices, triangles) the octree was voxelized from (with resolution or voxel_size): drawn, or shaded "
     "through the octree (surface)"},
};

/// One keyword as a call shows it.
struct KeywordInfo {
    std::string keyword;
    std::string identifier; ///< the library's name for it ("LevelSetOptions::exteriorBand"); empty for Python's own
    std::string doc;
    py::object fallback; ///< the default, as a Python value
    std::string names;   ///< the names an enum or channel set takes, quoted; else empty
};

/// Each option of a library struct, with its value (a default-constructed
/// struct's: the default) as a Python value.
struct Describe {
    std::vector<KeywordInfo>& out;

    void add(const svo::OptionInfo& i, py::object value, std::string names = {}) const
    {
        out.push_back({std::string(i.keyword), std::string(i.identifier), std::string(i.doc), std::move(value),
                       std::move(names)});
    }
    void operator()(const svo::OptionInfo& i, bool& v) const { add(i, py::bool_(v)); }
    void operator()(const svo::OptionInfo& i, std::string& v) const { add(i, py::str(v)); }
    template <typename E, typename = decltype(enumNames(E{}))>
    void operator()(const svo::OptionInfo& i, E& v) const
    {
        add(i, py::str(std::string(svo::nameOf(v))), svo::quotedNames<E>());
    }
    void operator()(const svo::OptionInfo& i, svo::CheckedNumber n) const { add(i, py::float_(n.value)); }
    template <typename Int, typename Read>
    void operator()(const svo::OptionInfo& i, svo::CheckedInteger<Int, Read> n) const
    {
        add(i, py::int_(n.value));
    }
    void operator()(const svo::OptionInfo& i, svo::NamedBool b) const
    {
        add(i, py::str(std::string(b.value ? b.trueName : b.falseName)),
            "'" + std::string(b.falseName) + "' or '" + std::string(b.trueName) + "'");
    }
    template <typename T>
    void operator()(const svo::OptionInfo& i, svo::OptionalNumber<T>) const
    {
        add(i, none()); // 0, "not given", is None in Python
    }
    void operator()(const svo::OptionInfo& i, svo::ByteCount c) const
    {
        add(i, c.bytes ? py::object(py::int_(c.bytes)) : none()); // 0: the device's free memory, None in Python
    }
    void operator()(const svo::OptionInfo& i, svo::RegionOption) const
    {
        add(i, none()); // the whole grid
    }
    void operator()(const svo::OptionInfo& i, svo::ChannelSet c) const
    {
        py::list set; // a tuple: a default Python can share between calls
        for (const auto& n : enumNames(svo::AttributeChannel{}))
            if (c.bits & n.value) set.append(py::str(std::string(n.name)));
        add(i, py::tuple(set), svo::quotedNames<svo::AttributeChannel>());
    }
};

/// Shows @a visit every option of the library structs Python's calls read,
/// each in a default-constructed struct (so a value seen is its default).
template <typename Visit>
void forEachLibraryOption(Visit&& visit)
{
    svo::GridRequest request;
    svo::VoxelizeSettings voxelize;
    svo::DeviceOptions device;
    svo::LevelSetOptions levelSet; // its SignOptions included
    svo::gl::ViewRequest view;     // its layers, AO and lighting too
    svo::GridOptions grids;        // write_nanovdb's topology, fog and codec
    forEachOption(request, visit);
    forEachOption(voxelize, visit);
    forEachOption(device, visit);
    forEachOption(levelSet, visit);
    forEachOption(view, visit);
    forEachOption(grids, visit);
#ifdef SVO_WITH_VALIDATE
    svo::validate::ReportOptions report;
    svo::validate::LevelSetReportOptions levelSetReport; // `worst` again: the same declaration
    forEachOption(report, visit);
    forEachOption(levelSetReport, visit);
#endif
}

/// Every keyword any call takes: Python's own, then the library's declared options.
std::vector<KeywordInfo> allKeywords()
{
    std::vector<KeywordInfo> out;
    for (const PythonKeyword& k : kPythonKeywords)
        out.push_back({std::string(k.keyword), {}, std::string(k.doc), k.fallback(), {}});
    forEachLibraryOption(Describe{out});
    return out;
}

/// The Python keyword of a library identifier ("LevelSetOptions::exteriorBand" -> "exterior_band"), for
/// Error::message; empty where none sets it.
std::string keywordOf(const std::string& identifier);

/// A call that takes keywords: the name its messages use and its keywords, in order.
struct Call {
    const char* name;
    std::vector<std::string_view> keywords;
};

const Call kDeviceCall{"Voxelizer", {"device", "gl_debug", "program_cache"}};
const Call kVoxelizeCall{"voxelize",
                         {"resolution", "voxel_size", "transform", "grid", "backend", "mode", "conservative",
                          "attributes", "gpu_memory", "region", "report"}};
const Call kOctreeCall{"octree",
                       {"resolution", "voxel_size", "transform", "backend", "mode", "conservative", "attributes",
                        "gpu_memory", "region"}};
const Call kLevelSetCall{"level_set",
                         {"resolution", "voxel_size", "transform", "exterior_band", "interior_band", "unsigned",
                          "closest_triangle", "sign", "winding_accuracy", "part_of_closed_mesh", "backend",
                          "gpu_memory", "region", "report"}};
const Call kSolidCall{"solid",
                      {"resolution", "voxel_size", "transform", "sign", "winding_accuracy", "part_of_closed_mesh",
                       "backend", "gpu_memory", "region", "report"}};
const Call kWriteNanoVdbCall{"write_nanovdb",
                             {"kind", "resolution", "voxel_size", "transform", "exterior_band", "interior_band", "closest_triangle",
                              "sign", "winding_accuracy", "part_of_closed_mesh", "backend", "mode", "conservative",
                              "attributes", "gpu_memory", "region", "topology", "fog", "codec"}};
const Call kBandCall{"band",
                     {"resolution", "voxel_size", "transform", "exterior_band", "backend", "gpu_memory", "region",
                      "report"}};
const Call kFromGridCall{"from_grid", {"backend"}};
const Call kRenderCall{"render",
                       {"size", "view", "layers", "levels", "color", "ao", "ao_only", "ao_source", "lighting", "lights",
                        "albedo", "specular", "mesh", "surface", "gi_emission", "gi_clearance", "ao_aperture",
                        "ao_offset", "ao_distance", "ao_step", "gi_cones", "gi_aperture", "gi_offset", "gi_step",
                        "gi_distance", "light_volume"}};
#ifdef SVO_WITH_VALIDATE
const Call kValidateCall{"validate",
                         {"resolution", "voxel_size", "transform", "backend", "conservative", "mode", "holes",
                          "strict", "worst"}};
const Call kValidateLevelSetCall{"validate_level_set",
                                 {"resolution", "voxel_size", "transform", "exterior_band", "interior_band", "sign",
                                  "winding_accuracy", "backend", "worst", "openvdb"}};
#endif

/// Every call by the name Python gives it, for svo._options().
const std::pair<const char*, const Call*> kCalls[] = {
    {"Voxelizer.__init__", &kDeviceCall},
    {"Voxelizer.voxelize", &kVoxelizeCall},
    {"Voxelizer.octree", &kOctreeCall},
    {"Voxelizer.level_set", &kLevelSetCall},
    {"Voxelizer.solid", &kSolidCall},
    {"Voxelizer.band", &kBandCall},
    {"Voxelizer.write_nanovdb", &kWriteNanoVdbCall},
    {"Octree.from_grid", &kFromGridCall},
    {"Octree.render", &kRenderCall},
    {"voxelize", &kVoxelizeCall},
#ifdef SVO_WITH_VALIDATE
    {"validate", &kValidateCall},
    {"validate_level_set", &kValidateLevelSetCall},
#endif
};

std::string keywordOf(const std::string& identifier)
{
    std::string keyword;
    const auto find = [&](const svo::OptionInfo& info, auto&&) {
        if (info.identifier != identifier) return;
        // Only a keyword some call takes: ViewRequest::render is svo view's --render, Python's lighting.
        for (const auto& [name, call] : kCalls)
            if (std::find(call->keywords.begin(), call->keywords.end(), info.keyword) != call->keywords.end())
                keyword = std::string(info.keyword);
    };
    forEachLibraryOption(find);
    return keyword;
}

/// The keywords of a call, in its order. A keyword declared nowhere is this
/// module's mistake: it fails the import (every docstring is made then).
std::vector<KeywordInfo> keywordsOf(const Call& call)
{
    const std::vector<KeywordInfo> all = allKeywords();
    std::vector<KeywordInfo> out;
    for (const std::string_view k : call.keywords) {
        const auto it = std::find_if(all.begin(), all.end(), [&](const KeywordInfo& i) { return i.keyword == k; });
        if (it == all.end())
            throw std::logic_error("svo: " + std::string(call.name) + "() lists keyword '" + std::string(k) +
                                   "', which nothing declares");
        out.push_back(*it);
    }
    return out;
}

/// @a text in lines of at most @a width characters, each after @a indent.
std::string wrapped(const std::string& text, const std::string& indent, size_t width = 100)
{
    std::string out, line;
    size_t start = 0;
    while (start < text.size()) {
        size_t end = text.find(' ', start);
        if (end == std::string::npos) end = text.size();
        const std::string word = text.substr(start, end - start);
        if (!line.empty() && indent.size() + line.size() + 1 + word.size() > width) {
            out += indent + line + "\n";
            line.clear();
        }
        line += (line.empty() ? "" : " ") + word;
        start = end + 1;
    }
    if (!line.empty()) out += indent + line + "\n";
    return out;
}

/// A call's docstring: @a summary, then each keyword with its default and its doc.
std::string docstring(const std::string& summary, const Call& call)
{
    std::string out = summary + "\n\nKeywords:\n";
    for (const KeywordInfo& k : keywordsOf(call)) {
        out += "    " + k.keyword + "=" + std::string(py::repr(k.fallback)) + "\n";
        std::string doc = k.doc;
        if (!k.names.empty()) doc += " (" + k.names + ")";
        out += wrapped(doc, "        ");
    }
    return out;
}

/// svo._options(): per call, each keyword's default (a Python value) and doc.
py::dict optionsTable()
{
    py::dict out;
    for (const auto& [name, call] : kCalls) {
        py::dict keywords;
        for (const KeywordInfo& k : keywordsOf(*call)) {
            py::dict entry;
            entry["default"] = k.fallback;
            entry["doc"] = k.doc;
            // The library's name for it (errors name the keyword instead: pythonMessage); None for Python's own.
            entry["identifier"] = k.identifier.empty() ? none() : py::object(py::str(k.identifier));
            keywords[py::str(k.keyword)] = entry;
        }
        out[name] = keywords;
    }
    return out;
}

/// The keywords one call was given: refused, as Python refuses them, unless
/// the call takes them; then read into library structs (read) or one by one (get).
class CallKeywords {
public:
    CallKeywords(const Call& call, const py::kwargs& given) : call_(call), given_(given)
    {
        for (const auto& item : given_) {
            const std::string name = py::cast<std::string>(item.first);
            if (!takes(name))
                throw py::type_error(std::string(call_.name) + "() got an unexpected keyword argument '" + name + "'");
        }
    }

    /// A keyword of Python's own: its value, or its default (kPythonKeywords).
    template <typename T>
    T get(std::string_view keyword) const
    {
        if (!takes(keyword)) throw std::logic_error("svo: " + std::string(call_.name) + "() reads an unlisted keyword");
        if (given(keyword)) return as<T>(keyword);
        for (const PythonKeyword& k : kPythonKeywords)
            if (k.keyword == keyword) return k.fallback().template cast<T>();
        throw std::logic_error("svo: keyword '" + std::string(keyword) + "' is not one of Python's own");
    }

    /// The options of @a options this call takes and was given, each read as its declaration says.
    template <typename Options>
    void read(Options& options) const
    {
        forEachOption(options, Reader{*this});
    }

private:
    bool takes(std::string_view keyword) const
    {
        return std::find(call_.keywords.begin(), call_.keywords.end(), keyword) != call_.keywords.end();
    }
    bool given(std::string_view keyword) const { return given_.contains(py::str(std::string(keyword))); }
    /// The keyword's value as T; a TypeError (as a mistyped argument was before) when it is not one.
    template <typename T>
    T as(std::string_view keyword) const
    {
        const py::object value = given_[py::str(std::string(keyword))];
        try {
            return value.template cast<T>();
        } catch (const py::cast_error&) {
            throw py::type_error(std::string(call_.name) + "(): keyword '" + std::string(keyword) +
                                 "' has the wrong type (" + std::string(py::str(value.get_type().attr("__name__"))) +
                                 ")");
        }
    }

    /// Sets each field whose keyword was given; the others keep the struct's defaults.
    struct Reader {
        const CallKeywords& kw;

        bool wanted(const svo::OptionInfo& i) const { return kw.takes(i.keyword) && kw.given(i.keyword); }
        void operator()(const svo::OptionInfo& i, bool& v) const
        {
            if (wanted(i)) v = kw.as<bool>(i.keyword);
        }
        void operator()(const svo::OptionInfo& i, std::string& v) const
        {
            if (wanted(i)) v = kw.as<std::string>(i.keyword);
        }
        template <typename E, typename = decltype(enumNames(E{}))>
        void operator()(const svo::OptionInfo& i, E& v) const
        {
            if (wanted(i)) v = svo::parse<E>(kw.as<std::string>(i.keyword), std::string(i.keyword));
        }
        void operator()(const svo::OptionInfo& i, svo::CheckedNumber n) const
        {
            if (!wanted(i)) return;
            const double v = kw.as<double>(i.keyword);
            n.rule(v, std::string(i.keyword)); // the library's rule, under the keyword
            n.value = v;
        }
        template <typename Int, typename Read>
        void operator()(const svo::OptionInfo& i, svo::CheckedInteger<Int, Read> n) const
        {
            if (!wanted(i)) return;
            const Read v = kw.as<Read>(i.keyword); // what the declared type cannot hold: a TypeError
            n.rule(int64_t(v), std::string(i.keyword));
            n.value = Int(v);
        }
        void operator()(const svo::OptionInfo& i, svo::NamedBool b) const
        {
            if (!wanted(i)) return;
            const std::string name = kw.as<std::string>(i.keyword);
            if (name != b.falseName && name != b.trueName)
                throw svo::InvalidInput(std::vector<svo::Error::Part>{
                    svo::Error::option(std::string(i.keyword)),
                    ": expected '" + std::string(b.falseName) + "' or '" + std::string(b.trueName) + "', got '" +
                        name + "'"});
            b.value = name == b.trueName;
        }
        template <typename T>
        void operator()(const svo::OptionInfo& i, svo::OptionalNumber<T> n) const
        {
            if (!wanted(i)) return;
            const auto v = kw.as<std::optional<double>>(i.keyword); // None: not given
            if (!v) return;
            n.rule(*v, std::string(i.keyword)); // the library's rule, under the keyword (8.5 refused, not cut)
            n.value = T(*v);
        }
        void operator()(const svo::OptionInfo& i, svo::ByteCount c) const
        {
            if (!wanted(i)) return;
            // Bytes as an int (a float was taken too), or None: what the device reports free.
            const auto bytes = kw.as<std::optional<double>>(i.keyword);
            if (bytes && !(*bytes >= 1 && *bytes <= 1e18))
                badValue(std::string(i.keyword) + ": expected a positive number of bytes or None");
            c.bytes = bytes ? uint64_t(*bytes) : 0;
        }
        void operator()(const svo::OptionInfo& i, svo::RegionOption r) const
        {
            if (!wanted(i)) return;
            // ((x0, y0, z0), (x1, y1, z1)), or None: the whole grid.
            const auto box = kw.as<std::optional<std::pair<std::array<int64_t, 3>, std::array<int64_t, 3>>>>(i.keyword);
            if (!box) return;
            const auto& [lo, hi] = *box;
            r.region = svo::regionFrom({lo[0], lo[1], lo[2], hi[0], hi[1], hi[2]}, std::string(i.keyword));
        }
        void operator()(const svo::OptionInfo& i, svo::ChannelSet c) const
        {
            if (!wanted(i)) return;
            c.bits = 0; // the channels given, not added to the default's
            for (const std::string& name : kw.as<std::vector<std::string>>(i.keyword))
                c.bits |= svo::parse<svo::AttributeChannel>(name, std::string(i.keyword));
        }
    };

    const Call& call_;
    const py::kwargs& given_;
};

/// Ctrl-C while the GIL is released: polled between the library's stages.
struct KeyboardInterrupter : openvdb::util::NullInterrupter {
    bool wasInterrupted(int) override
    {
        py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() == 0) return false;
        pending = true; // KeyboardInterrupt is set; raised once the call unwinds
        return true;
    }
    bool pending = false;
};

// --- the calls ---------------------------------------------------------------

/// Everything a voxelize() call needs, checked, before the GIL is released.
struct Request {
    svo::TriangleMesh mesh;
    svo::GridSpec grid;
    svo::GridRequest asked;              ///< resolution or voxel size as asked (neither: a transform)
    openvdb::math::Transform::Ptr xform; ///< the output grids' transform
};

/// The mesh and the grid of resolution=, voxel_size= or transform=.
Request makeRequest(const py::handle& vertices, const py::handle& triangles, const CallKeywords& kw)
{
    svo::GridRequest req;
    kw.read(req); // each number checked by its rule, under its keyword
    const auto transform = kw.get<py::object>("transform");
    const int given = int(req.resolution != 0) + int(req.voxelSize != 0) + int(!transform.is_none());
    if (given > 1) badValue("give one of resolution, voxel_size and transform");
    const std::vector<openvdb::Vec3d> points = toPoints(vertices);
    std::vector<openvdb::Vec3I> tris;
    std::vector<openvdb::Vec4I> quads;
    toFaces(triangles, points.size(), tris, quads);
    // The mesh or grid cannot be voxelized as asked: svo::InvalidInput, a ValueError.
    Request r;
    if (!transform.is_none()) {
        r.xform = toTransform(transform);
        svo::IndexSpaceMesh m = svo::prepareMesh(points, tris, quads, *r.xform);
        r.mesh = std::move(m.mesh);
        r.grid = m.grid;
        return r;
    }
    // resolution or voxel size: the mesh and the grid exactly as `svo voxelize`
    // has them (a file's mesh, then makeGrid), so both give the same voxels.
    r.mesh = svo::toTriangleMesh(points, tris, quads);
    r.mesh.source = "mesh";
    if (req.resolution == 0 && req.voxelSize == 0) req.resolution = svo::kDefaultResolution;
    r.asked = req;
    r.grid = svo::makeGrid(r.mesh, req);
    r.xform = svo::vdb::makeTransform(r.grid);
    return r;
}

svo::Octree run(svo::Voxelizer& v, const Request& r, const svo::VoxelizeSettings& settings,
                std::vector<uint64_t>* voxelList = nullptr, svo::VoxelizeStats* stats = nullptr)
{
    svo::VoxelizeOptions o;
    static_cast<svo::VoxelizeSettings&>(o) = settings;
    o.stats = stats;
    KeyboardInterrupter interrupter;
    o.interrupter = &interrupter;
    try {
        py::gil_scoped_release release;
        return v.voxelize(r.mesh, r.grid, o, voxelList);
    } catch (const svo::Interrupted&) {
        if (interrupter.pending) throw py::error_already_set(); // the KeyboardInterrupt
        throw;
    }
}

/// The octree's voxels as (K, 3) index coordinates in its voxel order: the
/// order of its attribute channels (bricks by index, bits within a brick).
py::array_t<int32_t> voxelOrder(const svo::Octree& octree)
{
    std::vector<std::array<uint32_t, 3>> origin(octree.bricks.size());
    for (const auto& ref : svo::occupiedBricks(octree)) origin[ref.index] = ref.origin;
    py::array_t<int32_t> out({py::ssize_t(octree.voxelCount()), py::ssize_t(3)});
    auto w = out.mutable_unchecked<2>();
    py::ssize_t k = 0;
    for (size_t b = 0; b < octree.bricks.size(); ++b)
        for (uint32_t bit = 0; bit < 512; ++bit)
            if (octree.bricks[b].words[bit >> 6] >> (bit & 63) & 1) {
                const auto g = octree.grid.toGlobal({origin[b][0] + (bit >> 6), origin[b][1] + (bit >> 3 & 7),
                                                     origin[b][2] + (bit & 7)});
                w(k, 0) = int32_t(g[0]), w(k, 1) = int32_t(g[1]), w(k, 2) = int32_t(g[2]);
                ++k;
            }
    return out;
}

/// (K, 3) float32 rows of @a values.
py::array_t<float> vectorArray(const std::vector<svo::Vec3f>& values)
{
    py::array_t<float> a({py::ssize_t(values.size()), py::ssize_t(3)});
    auto w = a.mutable_unchecked<2>();
    for (size_t i = 0; i < values.size(); ++i)
        w(py::ssize_t(i), 0) = values[i].x, w(py::ssize_t(i), 1) = values[i].y, w(py::ssize_t(i), 2) = values[i].z;
    return a;
}

/// The svo:* metadata `svo voxelize` writes (svo::resultMetadata), on each of @a grids.
void tagResult(const openvdb::GridPtrVec& grids, const Request& r, bool guardBand)
{
    for (const auto& [key, value] : svo::resultMetadata(r.mesh, r.grid, r.asked, guardBand))
        for (const auto& g : grids) g->insertMeta(key, openvdb::StringMetadata(svo::vdb::validUtf8(value)));
}

/// Result.report: what the call did, in the words of `svo voxelize --json`.
py::dict reportOf(const svo::VoxelizeStats& s, const openvdb::GridBase& main)
{
    py::dict d;
    d["active_voxels"] = main.activeVoxelCount();
    d["backend"] = s.backend;
    d["mode"] = s.mode;
    d["dilation"] = s.dilation;
    d["device"] = s.device;
    d["tiles"] = s.tiles;
    d["gpu_bytes"] = s.gpuBytes;
    d["epsilon"] = s.epsilon;
    d["sign"] = s.sign;
    d["open_columns"] = s.openColumns;
    d["band_bricks"] = s.bandBricks;
    d["winding_bricks"] = s.windingBricks;
    d["winding_walks"] = s.windingWalks;
    d["warnings"] = s.warnings;
    py::list stages;
    for (const svo::StageTime& t : s.stages) {
        py::dict stage;
        stage["name"] = t.name;
        stage["gpu_ms"] = t.gpuMs < 0 ? py::object(py::none()) : py::object(py::float_(t.gpuMs));
        stage["wall_ms"] = t.wallMs;
        stages.append(stage);
    }
    d["stages"] = stages;
    return d;
}

/// svo.Result (svo/_result.py), what every call that makes grids returns: the
/// main grid, every grid by name, the per-voxel arrays asked for, the report
/// asked for; None for what was not asked.
struct ResultParts {
    openvdb::GridPtrVec grids; ///< the main grid first
    py::object ijk = py::none(), normal = py::none(), color = py::none(), triangle = py::none(), report = py::none();
};

py::object makeResult(const ResultParts& p)
{
    py::dict byName;
    for (const auto& g : p.grids) byName[py::str(g->getName())] = toPython(g);
    return py::module_::import("svo._result")
        .attr("Result")(byName[py::str(p.grids.front()->getName())], byName, p.ijk, p.normal, p.color, p.triangle,
                        p.report);
}

py::object voxelizeWith(svo::Voxelizer& v, const py::handle& vertices, const py::handle& triangles,
                        const py::kwargs& kwargs)
{
    const CallKeywords kw(kVoxelizeCall, kwargs);
    const std::string grid = kw.get<std::string>("grid");
    if (grid != "bool" && grid != "fog") badValue("grid: expected 'bool' or 'fog', got '" + grid + "'");
    const bool wantReport = kw.get<bool>("report");
    svo::VoxelizeSettings settings;
    kw.read(settings);
    const Request r = makeRequest(vertices, triangles, kw);
    svo::VoxelizeStats stats;
    const svo::Octree octree = run(v, r, settings, nullptr, &stats);
    svo::GridOptions g;
    g.topology = svo::GridOptions::Topology::Bool; // pyopenvdb has no MaskGrid
    g.fog = grid == "fog";
    const openvdb::GridPtrVec all = svo::octreeToGrids(octree, g, r.xform);
    ResultParts out;
    out.grids.push_back(all[g.fog ? 1 : 0]);
    // Normals and colours as grids too, for writing beside the voxels; triangle
    // ids as an array only (pyopenvdb has no Int32Grid).
    for (const auto& gr : all)
        if (gr->getName() == "normal" || gr->getName() == "color") out.grids.push_back(gr);
    if (settings.attributes) {
        out.ijk = voxelOrder(octree); // the voxels in the order of the arrays below
        if (settings.attributes & svo::kTriangles) {
            py::array_t<int32_t> ids(py::ssize_t(octree.attributes.triangles.size()));
            std::copy(octree.attributes.triangles.begin(), octree.attributes.triangles.end(), ids.mutable_data());
            out.triangle = ids;
        }
        // Each channel computed, an empty array where no voxel holds it (an empty region).
        if (octree.channels() & svo::kNormals) out.normal = vectorArray(octree.attributes.normals);
        if (octree.channels() & svo::kColors) out.color = vectorArray(octree.attributes.colors);
    }
    tagResult(out.grids, r, true);
    if (wantReport) out.report = reportOf(stats, *out.grids.front());
    return makeResult(out);
}

/// Runs a level-set or solid call with the GIL released and Ctrl-C heard.
template <typename F>
auto runField(const svo::VoxelizeSettings& settings, F call, svo::VoxelizeStats* stats = nullptr)
{
    svo::VoxelizeOptions o;
    static_cast<svo::VoxelizeSettings&>(o) = settings;
    o.stats = stats;
    KeyboardInterrupter interrupter;
    o.interrupter = &interrupter;
    try {
        py::gil_scoped_release release;
        return call(o);
    } catch (const svo::Interrupted&) {
        if (interrupter.pending) throw py::error_already_set();
        throw;
    }
}

/// Python's default name of a level set: its own, apart from voxelize()'s "surface"
/// (the library names both "surface", as OpenVDB's tools do; one file may hold both).
constexpr const char* kLevelSetName = "level_set";

py::object levelSetWith(svo::Voxelizer& v, const py::handle& vertices, const py::handle& triangles,
                        const py::kwargs& kwargs)
{
    const CallKeywords kw(kLevelSetCall, kwargs);
    const bool wantReport = kw.get<bool>("report");
    svo::LevelSetOptions ls;
    kw.read(ls);
    svo::VoxelizeSettings settings;
    kw.read(settings);
    const Request r = makeRequest(vertices, triangles, kw);
    svo::VoxelizeStats stats;
    const openvdb::GridPtrVec grids = runField(
        settings, [&](const svo::VoxelizeOptions& o) { return v.levelSet(r.mesh, r.grid, ls, o, r.xform); }, &stats);
    ResultParts out;
    out.grids.push_back(grids.front());
    if (!ls.unsignedDistance) out.grids.front()->setName(kLevelSetName);
    tagResult(out.grids, r, false);
    if (ls.closestTriangle) {
        // pyopenvdb has no Int32Grid: the band's voxels and their triangles as arrays.
        const auto closest = openvdb::gridPtrCast<openvdb::Int32Grid>(grids.at(1));
        const auto n = py::ssize_t(closest->activeVoxelCount());
        py::array_t<int32_t> ijk({n, py::ssize_t(3)});
        py::array_t<int32_t> ids(n);
        auto c = ijk.mutable_unchecked<2>();
        auto id = ids.mutable_unchecked<1>();
        py::ssize_t i = 0;
        for (auto it = closest->cbeginValueOn(); it; ++it, ++i) {
            const openvdb::Coord xyz = it.getCoord();
            c(i, 0) = xyz.x(), c(i, 1) = xyz.y(), c(i, 2) = xyz.z();
            id(i) = *it;
        }
        out.ijk = ijk;
        out.triangle = ids;
    }
    if (wantReport) out.report = reportOf(stats, *out.grids.front());
    return makeResult(out);
}

/// A MaskGrid result (solid(), band()) as Python takes it: pyopenvdb has no
/// MaskGrid, so the same topology as a BoolGrid, true on it, with the
/// library's name and svo:* metadata (svo:sign: which sign method ran and why).
py::object maskResult(const openvdb::MaskGrid::Ptr& mask, const Request& r, const svo::VoxelizeStats& stats,
                      bool wantReport)
{
    auto grid = openvdb::BoolGrid::create(
        openvdb::BoolTree::Ptr(new openvdb::BoolTree(mask->tree(), false, true, openvdb::TopologyCopy())));
    grid->setTransform(mask->transform().copy());
    for (auto meta = mask->beginMeta(); meta != mask->endMeta(); ++meta) grid->insertMeta(meta->first, *meta->second);
    ResultParts out;
    out.grids.push_back(grid);
    tagResult(out.grids, r, false);
    if (wantReport) out.report = reportOf(stats, *grid);
    return makeResult(out);
}

py::object solidWith(svo::Voxelizer& v, const py::handle& vertices, const py::handle& triangles,
                     const py::kwargs& kwargs)
{
    const CallKeywords kw(kSolidCall, kwargs);
    svo::SignOptions signOptions;
    kw.read(signOptions);
    svo::VoxelizeSettings settings;
    kw.read(settings);
    const Request r = makeRequest(vertices, triangles, kw);
    svo::VoxelizeStats stats;
    const auto mask = runField(
        settings, [&](const svo::VoxelizeOptions& o) { return v.solid(r.mesh, r.grid, o, signOptions, r.xform); },
        &stats);
    return maskResult(mask, r, stats, kw.get<bool>("report"));
}

py::object bandWith(svo::Voxelizer& v, const py::handle& vertices, const py::handle& triangles,
                    const py::kwargs& kwargs)
{
    const CallKeywords kw(kBandCall, kwargs);
    svo::LevelSetOptions ls;
    kw.read(ls);
    svo::VoxelizeSettings settings;
    kw.read(settings);
    const Request r = makeRequest(vertices, triangles, kw);
    svo::VoxelizeStats stats;
    const auto mask = runField(
        settings, [&](const svo::VoxelizeOptions& o) { return v.band(r.mesh, r.grid, ls.exteriorBand, o, r.xform); },
        &stats);
    return maskResult(mask, r, stats, kw.get<bool>("report"));
}

/// Voxelizer.write_nanovdb: a kind's NanoVDB grids laid out by the library's
/// NanoVDB calls (on the GPU where they can be, as `svo voxelize -o x.nvdb`),
/// with no OpenVDB tree, written to @a path (atomically); returns its bytes.
uint64_t writeNanoVdbWith(svo::Voxelizer& v, const std::filesystem::path& path, const py::handle& vertices,
                          const py::handle& triangles, const py::kwargs& kwargs)
{
    const CallKeywords kw(kWriteNanoVdbCall, kwargs);
    const std::string file = path.string();
    if (svo::outputFormat(file) != svo::OutputFormat::NanoVdb)
        badValue(file + ": write_nanovdb writes .nvdb files (svo.write writes grids as .vdb)");
    if (!kw.get<py::object>("transform").is_none())
        badValue("transform: write_nanovdb takes resolution or voxel_size (a NanoVDB grid's transform here is a "
                 "voxel size and a translation)");
    const std::string kind = kw.get<std::string>("kind");
    if (kind != "surface" && kind != "sdf" && kind != "udf" && kind != "solid" && kind != "band")
        badValue("kind: expected 'surface', 'sdf', 'udf', 'solid' or 'band', got '" + kind + "'");
    svo::LevelSetOptions ls;
    kw.read(ls);
    ls.unsignedDistance = kind == "udf";
    svo::VoxelizeSettings settings;
    kw.read(settings);
    svo::GridOptions grids;
    kw.read(grids);
    const Request r = makeRequest(vertices, triangles, kw);
    const auto nano = runField(settings, [&](const svo::VoxelizeOptions& o) {
        if (kind == "surface") return v.voxelizeNanoVdb(r.mesh, r.grid, o, grids);
        if (kind == "solid" || kind == "band") {
            std::vector<svo::vdb::NanoHandle> out;
            if (kind == "solid") out.push_back(v.solidNanoVdb(r.mesh, r.grid, o, ls.sign, grids.topology));
            else out.push_back(v.bandNanoVdb(r.mesh, r.grid, ls.exteriorBand, o, grids.topology));
            return out;
        }
        return v.levelSetNanoVdb(r.mesh, r.grid, ls, o);
    });
    py::gil_scoped_release release;
    return svo::vdb::writeNanoVdb(file, nano, grids.codec);
}

/// (K, 3) int32 index coordinates of a grid's active voxels, tiles expanded,
/// in OpenVDB's tree order; any transform.
py::array_t<int32_t> activeVoxels(const py::handle& obj)
{
    const openvdb::GridBase::Ptr grid = gridArgument(obj, "grid");
    std::vector<int32_t> coords;
    {
        py::gil_scoped_release release;
        grid->apply<GridTypes>([&](const auto& g) {
            coords.reserve(3 * g.activeVoxelCount());
            for (auto it = g.tree().cbeginValueOn(); it; ++it) {
                openvdb::CoordBBox box;
                it.getBoundingBox(box); // one voxel, or a whole active tile
                for (auto c = box.begin(); c; ++c) coords.insert(coords.end(), {(*c).x(), (*c).y(), (*c).z()});
            }
        });
    }
    py::array_t<int32_t> out({py::ssize_t(coords.size() / 3), py::ssize_t(3)});
    std::copy(coords.begin(), coords.end(), out.mutable_data());
    return out;
}

py::tuple readMesh(const std::filesystem::path& path)
{
    svo::TriangleMesh m;
    {
        py::gil_scoped_release release;
        m = svo::loadMesh(path.string()); // svo::IoError: an OSError
    }
    py::array_t<double> v({py::ssize_t(m.positions.size()), py::ssize_t(3)});
    py::array_t<uint32_t> t({py::ssize_t(m.triangles.size()), py::ssize_t(3)});
    auto vr = v.mutable_unchecked<2>();
    auto tr = t.mutable_unchecked<2>();
    for (size_t i = 0; i < m.positions.size(); ++i)
        vr(py::ssize_t(i), 0) = m.positions[i].x, vr(py::ssize_t(i), 1) = m.positions[i].y,
                        vr(py::ssize_t(i), 2) = m.positions[i].z;
    for (size_t i = 0; i < m.triangles.size(); ++i)
        for (int c = 0; c < 3; ++c) tr(py::ssize_t(i), c) = m.triangles[i][size_t(c)];
    return py::make_tuple(v, t);
}

/// An octree and the transform its index space belongs to.
struct PyOctree {
    svo::Octree octree;
    openvdb::math::Transform::Ptr xform;
};

/// The headless context pictures are drawn with, made on first use and kept
/// for the process (EGL is not torn down while the interpreter exits).
const svo::gl::Context& pictureContext()
{
    static const auto* context = new svo::gl::Context();
    return *context;
}

/// A number, or three (r, g, b), as svo's colours and light powers.
svo::Vec3d colorOf(const py::handle& h, const std::string& what)
{
    if (py::isinstance<py::float_>(h) || py::isinstance<py::int_>(h)) {
        const double v = py::cast<double>(h);
        return {v, v, v};
    }
    try {
        const auto c = py::cast<std::array<double, 3>>(h);
        return {c[0], c[1], c[2]};
    } catch (const py::cast_error&) {
        badValue(what + ": expected a number or (r, g, b)");
    }
}

/// [('sun', (dx, dy, dz)[, E]) or ('point', (x, y, z)[, I]), ...], as svo
/// view --light: a sun travelling along d with irradiance E, a point light
/// of intensity I; E and I a number or (r, g, b), pi by default.
svo::Lights lightsOf(const py::iterable& list)
{
    const std::string form = "lights: each light is ('sun', (dx, dy, dz)[, E]) or ('point', (x, y, z)[, I])";
    svo::Lights out;
    for (const py::handle& item : list) {
        if (!py::isinstance<py::tuple>(item) && !py::isinstance<py::list>(item)) badValue(form);
        const py::sequence t = py::reinterpret_borrow<py::sequence>(item);
        if (t.size() < 2 || t.size() > 3 || !py::isinstance<py::str>(t[0])) badValue(form);
        const std::string kind = py::cast<std::string>(t[0]);
        std::array<double, 3> v{};
        try {
            v = py::cast<std::array<double, 3>>(t[1]);
        } catch (const py::cast_error&) {
            badValue(form);
        }
        const svo::Vec3d power = t.size() == 3 ? colorOf(t[2], "lights") : svo::Vec3d{M_PI, M_PI, M_PI};
        if (kind == "sun") out.directional.push_back({{v[0], v[1], v[2]}, power});
        else if (kind == "point") out.point.push_back({{v[0], v[1], v[2]}, power});
        else badValue(form + ", got '" + kind + "'");
    }
    return out;
}

/// The Python words for the library's other names in render's messages: its render mode is
/// Python's lighting, channels and values of keywords.
std::string keywordFor(const std::string& identifier)
{
    static const std::pair<const char*, const char*> keywords[] = {
        {"ViewRequest::render", "lighting"},          {"svo::kNormals", "attributes=['normal']"},
        {"svo::kColors", "attributes=['color']"},     {"svo::kTriangles", "attributes=['triangle']"},
        {"AmbientOcclusion::volumeResolution", "light_volume"},
        {"AmbientOcclusion::Source::Octree", "ao_source='octree'"}};
    for (const auto& [id, keyword] : keywords)
        if (identifier == id) return keyword;
    return {};
}

/// An error's message with the Python keyword for each library identifier it names: a declared
/// option's (keywordOf), else render's (keywordFor), else the library's own words.
std::string pythonMessage(const svo::Error& e)
{
    return e.message([](const std::string& identifier) {
        const std::string keyword = keywordOf(identifier);
        return keyword.empty() ? keywordFor(identifier) : keyword;
    });
}

/// The mesh=(vertices, triangles) keyword, in the octree's frame.
std::optional<svo::TriangleMesh> renderMesh(const PyOctree& p, const py::object& mesh)
{
    if (mesh.is_none()) return std::nullopt;
    if (!py::isinstance<py::sequence>(mesh) || py::len(mesh) != 2)
        badValue("mesh: expected (vertices, triangles), the arrays the octree was voxelized from");
    const auto parts = mesh.cast<py::sequence>();
    if (*p.xform != *svo::vdb::makeTransform(p.octree.grid))
        badValue("mesh: the octree's transform is not a uniform voxel size and a whole-voxel translation, so "
                 "its triangles cannot be placed in it (voxelize it with resolution or voxel_size)");
    const std::vector<openvdb::Vec3d> points = toPoints(parts[0]);
    std::vector<openvdb::Vec3I> tris;
    std::vector<openvdb::Vec4I> quads;
    toFaces(parts[1], points.size(), tris, quads);
    svo::TriangleMesh m;
    m.source = "mesh";
    for (const auto& q : points) m.positions.push_back({q.x(), q.y(), q.z()});
    for (const auto& t : tris) m.triangles.push_back({uint32_t(t.x()), uint32_t(t.y()), uint32_t(t.z())});
    for (const auto& q : quads) {
        m.triangles.push_back({uint32_t(q[0]), uint32_t(q[1]), uint32_t(q[2])});
        m.triangles.push_back({uint32_t(q[0]), uint32_t(q[2]), uint32_t(q[3])});
    }
    return m;
}

/// Octree.render(**keywords): one frame of the octree view, (H, W, 4) uint8,
/// rows from the top. The keywords fill a view request (svo/gl/view_request.h),
/// as svo view's flags do; the library applies the defaults and the checks.
py::array_t<uint8_t> renderOctree(const PyOctree& p, const py::kwargs& kwargs)
{
    namespace gl = svo::gl;
    const CallKeywords kw(kRenderCall, kwargs);
    gl::ViewRequest request;
    kw.read(request); // the declared options (svo/gl/view_request.h), each checked as it is read
    const auto [width, height] = kw.get<std::pair<int, int>>("size");
    const std::string view = kw.get<std::string>("view");
    gl::ViewLayers& l = request.layers;
    l.voxels = l.outlines = false;
    for (const std::string& name : kw.get<std::vector<std::string>>("layers")) {
        if (name == "voxels") l.voxels = true;
        else if (name == "outlines") l.outlines = true;
        else if (name == "bricks") l.bricks = true;
        else badValue("layers: expected 'voxels', 'outlines' or 'bricks', got '" + name + "'");
    }
    if (const auto levels = kw.get<std::optional<std::pair<int, int>>>("levels")) {
        if (levels->first < 0 || levels->second < levels->first)
            badValue("levels: expected (first, last) with 0 <= first <= last");
        l.firstLevel = uint32_t(levels->first);
        l.lastLevel = uint32_t(levels->second);
    }
    l.ao.only = kw.get<bool>("ao_only"); // AO alone, the layers kept
    l.ao.volumeResolution = l.light.volumeResolution; // light_volume: one volume for AO and light
    const gl::Illumination::Mode lighting = svo::parse<gl::Illumination::Mode>(kw.get<std::string>("lighting"), "lighting");
    request.render = lighting == gl::Illumination::Mode::Global   ? gl::RenderMode::Global
                     : lighting == gl::Illumination::Mode::Direct ? gl::RenderMode::Direct
                                                                  : gl::RenderMode::Layers;
    const bool lit = gl::isLit(request.render);
    if (const auto lights = kw.get<py::object>("lights"); !lights.is_none()) {
        if (!py::isinstance<py::iterable>(lights)) throw py::type_error("render(): lights: expected a list of lights");
        request.lights = lightsOf(lights);
    }
    const auto albedo = kw.get<py::object>("albedo"), specular = kw.get<py::object>("specular");
    if (!albedo.is_none()) l.light.albedo = colorOf(albedo, "albedo");
    if (!specular.is_none()) l.light.specular = colorOf(specular, "specular");
    std::optional<svo::TriangleMesh> triangles = renderMesh(p, kw.get<py::object>("mesh"));
    // Keywords that light the voxels, given without lighting.
    const gl::Illumination gi;
    if (!lit) {
        if (request.lights || !albedo.is_none() || !specular.is_none() || l.light.directional || l.light.clearance)
            badValue("lights, albedo, specular, gi_emission and gi_clearance light the voxels of lighting='direct' or "
                     "'gi'");
        if (l.light.cones != gi.cones || l.light.apertureDegrees != gi.apertureDegrees || l.light.offset != gi.offset ||
            l.light.step != gi.step || l.light.distance != gi.distance)
            badValue("gi_cones, gi_aperture, gi_offset, gi_step and gi_distance shape the bounce of lighting='gi'");
    }
    if (width < 1 || height < 1 || width > 16384 || height > 16384)
        badValue("size: expected (width, height), 1 to 16384 pixels each");
    // An svo::InvalidInput names render's keywords through the translator (pythonMessage).
    const gl::ViewLayers shown = gl::viewLayers(request, p.octree, triangles.has_value());
    const gl::ViewCamera camera = gl::namedView(gl::gridWorldBox(p.octree.grid), view, double(width) / double(height));
    gl::Image image;
    {
        py::gil_scoped_release release;
        const gl::OctreeView v(pictureContext(), p.octree, triangles ? &*triangles : nullptr);
        image = v.render(camera, width, height, shown);
    }
    py::array_t<uint8_t> out({py::ssize_t(height), py::ssize_t(width), py::ssize_t(4)});
    std::copy(image.rgba.begin(), image.rgba.end(), out.mutable_data());
    return out;
}

PyOctree octreeWith(svo::Voxelizer& v, const py::handle& vertices, const py::handle& triangles,
                    const py::kwargs& kwargs)
{
    const CallKeywords kw(kOctreeCall, kwargs);
    svo::VoxelizeSettings settings;
    kw.read(settings);
    const Request r = makeRequest(vertices, triangles, kw);
    return PyOctree{run(v, r, settings), r.xform};
}

PyOctree octreeFromGrid(const py::handle& obj, const py::kwargs& kwargs)
{
    const CallKeywords kw(kFromGridCall, kwargs);
    svo::VoxelizeOptions o;
    kw.read(static_cast<svo::VoxelizeSettings&>(o));
    const openvdb::GridBase::Ptr grid = gridArgument(obj, "grid");
    py::gil_scoped_release release;
    svo::Voxelizer v;
    return PyOctree{v.gridToOctree(*grid, o), grid->transform().copy()};
}

/// A numpy view of `count` rows of `cols` values at `data`, kept alive by `owner`.
template <typename T>
py::array view(const void* data, size_t count, size_t cols, const py::handle& owner)
{
    return py::array_t<T>({py::ssize_t(count), py::ssize_t(cols)}, {py::ssize_t(cols * sizeof(T)), py::ssize_t(sizeof(T))},
                          static_cast<const T*>(data), owner);
}

#ifdef SVO_WITH_VALIDATE
/// The voxelization checked against CGAL's exact reference: the numbers of `svo validate --json`.
py::object validateWith(const py::handle& vertices, const py::handle& triangles, const py::kwargs& kwargs)
{
    const CallKeywords kw(kValidateCall, kwargs);
    svo::VoxelizeSettings settings;
    kw.read(settings);
    svo::validate::ReportOptions ro;
    kw.read(ro); // holes, strict, worst
    ro.mode = settings.mode;
    const Request r = makeRequest(vertices, triangles, kw);
    svo::Voxelizer v;
    std::vector<uint64_t> list;
    const svo::Octree octree = run(v, r, settings, &list);
    std::string text;
    {
        py::gil_scoped_release release;
        text = svo::validate::reportJson(svo::validate::validateVoxelization(r.mesh, octree, list, ro));
    }
    return py::module_::import("json").attr("loads")(text);
}
#endif

#ifdef SVO_WITH_VALIDATE
/// The GPU level set checked against CGAL and beside OpenVDB's meshToLevelSet:
/// the numbers of `svo validate --sdf --json`.
py::object validateLevelSetWith(const py::handle& vertices, const py::handle& triangles, const py::kwargs& kwargs)
{
    const CallKeywords kw(kValidateLevelSetCall, kwargs);
    svo::LevelSetOptions ls;
    kw.read(ls);
    svo::VoxelizeSettings settings;
    kw.read(settings);
    svo::validate::LevelSetReportOptions ro;
    kw.read(ro); // worst, openvdb
    const Request r = makeRequest(vertices, triangles, kw);
    svo::Voxelizer v;
    svo::VoxelizeStats stats;
    const openvdb::GridPtrVec grids = runField(settings, [&](svo::VoxelizeOptions o) {
        o.stats = &stats;
        return v.levelSet(r.mesh, r.grid, ls, o, r.xform);
    });
    std::string text;
    {
        py::gil_scoped_release release;
        const auto sdf = openvdb::gridPtrCast<openvdb::FloatGrid>(grids.front());
        ro.check.exteriorBand = ls.exteriorBand;
        ro.check.interiorBand = ls.interiorBand;
        ro.check.voxelSize = sdf->transform().voxelSize()[0]; // world units per voxel of the values
        ro.sign = stats.sign;
        text = svo::validate::levelSetReportJson(
            svo::validate::validateLevelSet(r.mesh, r.grid, svo::validate::activeLevelSetVoxels(*sdf), ro));
    }
    return py::module_::import("json").attr("loads")(text);
}
#endif

/// What voxelize() does; its keywords follow, from their declarations (docstring()).
constexpr const char* kVoxelizeDoc = R"doc(Voxelize a triangle mesh on the GPU into a grid.

With mode "conservative" (the default) the result holds every voxel whose
closed cube touches a triangle (the 26-separating voxelization); with "thin",
every voxel one of whose three axis-aligned centre segments (one voxel long)
touches one (6-separating, fewer voxels). Beyond that set there are at most
voxels within a tiny stated guard band of a triangle.

Args:
    vertices: (N, 3) array-like of float32/float64 world positions.
    triangles: (M, 3) integer array of vertex indices, or (M, 4) quads.

Returns:
    An svo.Result: .grid, a BoolGrid "surface" (FloatGrid "density" with
    grid="fog"), pyopenvdb's where it imports, else an svo.Grid; .grids, every
    grid by name ("normal" and "color" Vec3SGrids with those attributes);
    with attributes, .ijk ((K, 3) int32 voxel coordinates) and, in the same
    order, .triangle ((K,) int32 smallest triangle id), .normal and .color
    ((K, 3) float32); with report=True, .report. What was not asked is None.

Raises:
    ValueError: a bad array, index, transform or option.
    TypeError: a keyword the call does not take, or of the wrong type.
    RuntimeError: the GPU failed (no context, a driver limit).
    svo.OutOfMemoryError: GPU or host memory, or gpu_memory, cannot hold the
        work (a MemoryError, and a RuntimeError).
    NotImplementedError: a request svo has no method for (a RuntimeError).
    KeyboardInterrupt: Ctrl-C during the call (the Voxelizer stays usable).)doc";

} // namespace

PYBIND11_MODULE(_svo, m)
{
    m.doc() = "svo: GPU voxelization of triangle meshes into OpenVDB grids (see help(svo.voxelize)).";
    m.attr("__version__") = svo::version();
    // svo/__init__.py imports pyopenvdb, where it can, before this module is
    // loaded: with this module loaded first, OpenVDB's grid registration
    // crashed (whoever called it; not root-caused). Then this initialize()
    // finds the work done; without pyopenvdb it does the work.
    havePyopenvdb();
    openvdb::initialize();

    // svo's errors by type (see the top of this file). Out of memory is
    // svo.OutOfMemoryError: a MemoryError, and a RuntimeError as it was.
    static PyObject* outOfMemory = [] {
        PyObject* bases = PyTuple_Pack(2, PyExc_MemoryError, PyExc_RuntimeError);
        PyObject* type = PyErr_NewExceptionWithDoc(
            "svo._svo.OutOfMemoryError",
            "Host or GPU memory, or the gpu_memory budget, cannot hold the work: a MemoryError, and a "
            "RuntimeError (as svo raised it before).",
            bases, nullptr);
        Py_XDECREF(bases);
        return type;
    }();
    if (!outOfMemory) throw py::error_already_set();
    m.attr("OutOfMemoryError") = py::reinterpret_borrow<py::object>(outOfMemory);
    py::register_exception_translator([](std::exception_ptr p) {
        try {
            if (p) std::rethrow_exception(p);
        } catch (const svo::Interrupted& e) {
            PyErr_SetString(PyExc_KeyboardInterrupt, pythonMessage(e).c_str());
        } catch (const svo::InvalidInput& e) {
            PyErr_SetString(PyExc_ValueError, pythonMessage(e).c_str());
        } catch (const svo::IoError& e) {
            PyErr_SetString(PyExc_OSError, pythonMessage(e).c_str());
        } catch (const svo::OutOfMemory& e) {
            PyErr_SetString(outOfMemory, pythonMessage(e).c_str());
        } catch (const svo::Unsupported& e) {
            PyErr_SetString(PyExc_NotImplementedError, pythonMessage(e).c_str());
        } catch (const svo::Error& e) { // svo::DeviceError
            PyErr_SetString(PyExc_RuntimeError, pythonMessage(e).c_str());
        }
    });

    bindGrid(m);

    py::class_<svo::Voxelizer>(m, "Voxelizer",
                               "A reusable GPU voxelizer: keeps its GL context, compiled programs and buffers, so "
                               "later calls pay only for their work. Use one per thread.")
        .def(py::init([](const py::kwargs& kwargs) {
                 const CallKeywords kw(kDeviceCall, kwargs);
                 svo::DeviceOptions device;
                 kw.read(device);
                 return svo::Voxelizer(device);
             }),
             docstring("A Voxelizer on the EGL device the keywords choose (made on its first call).", kDeviceCall)
                 .c_str())
        .def("voxelize", &voxelizeWith, py::arg("vertices"), py::arg("triangles"),
             docstring(kVoxelizeDoc, kVoxelizeCall).c_str())
        .def("octree", &octreeWith, py::arg("vertices"), py::arg("triangles"),
             docstring("The voxels of a mesh as an svo.Octree (as voxelize()).", kOctreeCall).c_str())
        .def("level_set", &levelSetWith, py::arg("vertices"), py::arg("triangles"),
             docstring("A narrow-band signed distance field on the GPU, as OpenVDB's meshToLevelSet, in an\n"
                       "svo.Result: .grid, a FloatGrid 'level_set' of class GRID_LEVEL_SET, world-unit distances,\n"
                       "negative inside, exact to float rounding. unsigned=True gives unsigned distances (grid\n"
                       "'distance') for any mesh. closest_triangle=True adds .ijk, the band's voxels ((N, 3) int32\n"
                       "index coordinates), and .triangle, each one's nearest triangle ((N,) int32). The grid's\n"
                       "metadata 'svo:sign' says which sign method ran and why. Arrays as voxelize(); a\n"
                       "transform must have uniform scale.",
                       kLevelSetCall)
                 .c_str())
        .def("solid", &solidWith, py::arg("vertices"), py::arg("triangles"),
             docstring("The solid a mesh bounds, in an svo.Result whose .grid is a BoolGrid 'solid': the surface voxels and every voxel\n"
                       "whose centre is inside; regions wholly inside are active tiles; metadata 'svo:sign' as\n"
                       "level_set(). Arrays as voxelize().",
                       kSolidCall)
                 .c_str())
        .def("band", &bandWith, py::arg("vertices"), py::arg("triangles"),
             docstring("The voxels whose centres are nearer than exterior_band voxels to a triangle, in an svo.Result\n"
                       "whose .grid is a BoolGrid 'band': exactly the active voxels of level_set(unsigned=True) with\n"
                       "that band, without distances; any mesh. Arrays as voxelize().",
                       kBandCall)
                 .c_str())
        .def("write_nanovdb", &writeNanoVdbWith, py::arg("path"), py::arg("vertices"), py::arg("triangles"),
             docstring("Write a mesh's grids of one kind straight to a NanoVDB file (.nvdb), as svo voxelize -o\n"
                       "x.nvdb: laid out with no OpenVDB tree, on the GPU where the backend runs there (surfaces'\n"
                       "topology and fog, unsigned fields, level sets of closed meshes), the same bytes as on the\n"
                       "CPU; atomically (a temporary file renamed). Grids: 'surface' (topology, 'density' with\n"
                       "fog=True, the attributes' channels), 'surface' (class LEVEL_SET) or 'distance' and\n"
                       "'closest_triangle', 'solid', or 'band' (the voxels nearer than exterior_band to a triangle).\n"
                       "Returns the file's size in bytes.",
                       kWriteNanoVdbCall)
                 .c_str())
        .def("device", &svo::Voxelizer::deviceDescription, "The GPU's vendor, renderer and version.");

    py::class_<PyOctree>(m, "Octree",
                         "svo's sparse voxel octree: one array of nodes (child, child mask), children c = x + 2y + "
                         "4z, and 8^3 bricks of OpenVDB leaf masks. Make one with Voxelizer.octree(), "
                         "Octree.from_grid() or svo.load().")
        .def_static("from_grid", &octreeFromGrid, py::arg("grid"),
                    docstring("The active voxels of a pyopenvdb grid (uniform voxel size, whole-voxel "
                              "translation) as an octree.",
                              kFromGridCall)
                        .c_str())
        .def_property_readonly("nodes", [](py::object self) {
            const auto& o = self.cast<const PyOctree&>().octree;
            return view<uint32_t>(o.nodes.data(), o.nodes.size(), 2, self);
        }, "(N, 2) uint32 view of the nodes: (first child or brick index, child mask). No copy; valid while the octree lives.")
        .def_property_readonly("bricks", [](py::object self) {
            const auto& o = self.cast<const PyOctree&>().octree;
            return view<uint64_t>(o.bricks.data(), o.bricks.size(), 8, self);
        }, "(B, 8) uint64 view of the bricks: OpenVDB LeafNode<T,3> masks, bit (x&7)<<6 | (y&7)<<3 | (z&7). No copy.")
        .def_property_readonly("level_start", [](const PyOctree& p) { return p.octree.levelStart; },
                               "First node of each level; the last entry is the node count.")
        .def_property_readonly("levels", [](const PyOctree& p) { return p.octree.brickLevel + 1; },
                               "Levels from the root (0) to the bricks.")
        .def_property_readonly("voxel_count", [](const PyOctree& p) { return p.octree.voxelCount(); })
        .def("voxels", [](const PyOctree& p) { return voxelOrder(p.octree); },
             "(K, 3) int32 index coordinates, in the order of the attribute channels.")
        .def("to_grid", [](const PyOctree& p, const std::string& grid) {
            if (grid != "bool" && grid != "fog") badValue("grid: expected 'bool' or 'fog', got '" + grid + "'");
            svo::GridOptions g;
            g.topology = svo::GridOptions::Topology::Bool;
            g.fog = grid == "fog";
            g.attributes = false;
            return toPython(svo::octreeToGrids(p.octree, g, p.xform)[g.fog ? 1 : 0]);
        }, py::arg("grid") = "bool", "A grid of the voxels with the octree's transform (pyopenvdb's where it imports, else svo.Grid).")
        .def("render", &renderOctree,
             docstring("A picture of the octree drawn on the GPU, as svo view --screenshot draws it: (H, W, 4) "
                       "uint8,\nrows from the top. The keywords are svo view's options of the same names (--ao-step "
                       "for\nao_step), declared once for both.",
                       kRenderCall)
                 .c_str())
        .def("save", [](const PyOctree& p, const std::filesystem::path& file) {
            const std::string path = file.string();
            if (*p.xform != *svo::vdb::makeTransform(p.octree.grid))
                badValue("save: a .svo file holds a uniform voxel size and a whole-voxel translation; this octree's "
                         "transform is neither, so write its grid with pyopenvdb instead");
            svo::writeOctreeFile(path, p.octree); // svo::IoError: an OSError
        }, py::arg("path"), "Write a .svo file (versioned, checksummed), atomically; path a str or os.PathLike.");
    m.def("load", [](const std::filesystem::path& path) {
        svo::Octree o = svo::readOctreeFile(path.string()); // svo::IoError: an OSError
        auto xform = svo::vdb::makeTransform(o.grid);
        return PyOctree{std::move(o), xform};
    }, py::arg("path"), "Read a .svo file; a damaged or inconsistent file raises OSError naming the problem.");

    m.def(
        "voxelize",
        [](const py::handle& vertices, const py::handle& triangles, const py::kwargs& kwargs) {
            svo::Voxelizer v;
            return voxelizeWith(v, vertices, triangles, kwargs);
        },
        py::arg("vertices"), py::arg("triangles"),
        docstring(std::string("One-off call with a Voxelizer made for it (keep a Voxelizer for repeated calls).\n") +
                      kVoxelizeDoc,
                  kVoxelizeCall)
            .c_str());
#ifdef SVO_WITH_VALIDATE
    m.def("validate", &validateWith, py::arg("vertices"), py::arg("triangles"),
          docstring("Voxelize the mesh and check it against CGAL's exact tests, as `svo validate` does (triangle/box "
                    "for\nmode 'conservative', triangle/segment and a 6-connected hole fill for 'thin'): a dict with "
                    "mode,\nvoxels, required (R), exact (E), allowed (A), missed (R \\ G), missed_exact (E \\ G), "
                    "boundary,\nextra, worst_missed, worst_extra, holes (applies, leak, path, ...), "
                    "octree_consistent,\nepsilon, passed and reason.",
                    kValidateCall)
              .c_str());
    m.def("validate_level_set", &validateLevelSetWith, py::arg("vertices"), py::arg("triangles"),
          docstring("Make the level set (as Voxelizer.level_set) and check it as `svo validate --sdf` does: CGAL's "
                    "exact\ndistance at every active voxel, CGAL's side on closed meshes, and the band both ways, "
                    "with a\ntolerance of 1e-4 voxel; beside OpenVDB's meshToLevelSet when openvdb=True. A dict with "
                    "max_error,\nrms_error, over_tolerance, sign_checked, sign_reason, sign_disagreements, "
                    "sign_near_surface,\nmissing, extra, band_unjudged, the worst cases, openvdb (active, common, "
                    "only_svo, only_openvdb,\nsign_disagreements, max_difference, ...), passed and reason.",
                    kValidateLevelSetCall)
              .c_str());
#endif
    m.def("_grid_bytes", [](const py::handle& grid) { return gridArray(gridArgument(grid, "grid")); },
          py::arg("grid"),
          "The grid as a uint8 array of an OpenVDB stream (active-mask compression only), for svo.distributed.");
    m.def("_grid_from_bytes", [](const py::buffer& b) { return toPython(gridFromBytes(b)); }, py::arg("bytes"),
          "The grid of _grid_bytes' bytes, as results give grids (pyopenvdb's where it imports, else svo.Grid).");
    m.def("_join_region", &joinRegion, py::arg("into"), py::arg("part"),
          "Internal (svo.distributed): move the grid of a region into the grid of other regions it does not "
          "meet, keeping its leaves, its active tiles and its inactive tiles that are not background; `part` is "
          "left empty.");
    m.def("_options", &optionsTable,
          "Internal: per call ('Voxelizer.voxelize', 'voxelize', ...), each keyword's default and doc, from the "
          "declarations the calls read their keywords by (the stub's test compares them).");
    m.def("active_voxels", &activeVoxels, py::arg("grid"),
          "The index coordinates of a grid's active voxels (tiles expanded) as a (K, 3) int32 array, in "
          "OpenVDB's tree order; any transform.");
    // The formats as the readers list them (svo::supportedMeshExtensions), written once; kept for the process.
    static const std::string readMeshDoc =
        std::string("Read a mesh file (") + svo::supportedMeshExtensions() +
        ") with svo's readers: (vertices float64 (N, 3), triangles uint32 (M, 3)); a glTF file gives its default "
        "scene's triangles with the node transforms applied. Raises OSError naming the file and the problem.";
    m.def("read_mesh", &readMesh, py::arg("path"), readMeshDoc.c_str());
}
