// VTK XML writers (.vtu, .vtm with .vtp per patch): vtk_xml.h. Written by hand rather than
// through VTK: the format is a small XML header and raw arrays, and Strata would otherwise link
// all of VTK for it. Every array goes raw into one <AppendedData> block, each preceded by its
// byte count as UInt64 (header_type), little-endian; the header gives each array's offset in
// the block. Uncompressed: ParaView reads it straight into memory, and the files are as
// deterministic as the mesh.

#include <strata/core/cell_quality.h>
#include <strata/core/error.h>
#include <strata/core/face_match.h>
#include <strata/core/mesh_check.h>
#include <strata/core/solver_checks.h>
#include <strata/io/formats.h>
#include <strata/io/vtk_xml.h>

#include "buffered_file.h"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cstring>
#include <string>
#include <string_view>
#include <vector>

namespace strata {
namespace {

static_assert(__BYTE_ORDER__ == __ORDER_LITTLE_ENDIAN__, "the VTK files are written as little-endian");

/// VTK's cell type codes, by CellType.
constexpr std::array<std::uint8_t, 4> kVtkCellType{10, 14, 13, 12};  // tetra, pyramid, wedge, hexahedron
/// VTK's wedge has its first triangle's right-hand normal pointing away from the second, Gmsh's
/// prism towards it: the triangles reversed.
constexpr std::array<int, 6> kWedgeOrder{0, 2, 1, 3, 5, 4};

/// One array of a dataset: its XML tag's attributes and its raw bytes.
struct DataArray {
    std::string name;
    std::string type;  ///< VTK's: Float64, Int64, Int32, UInt8, String
    int components = 1;
    std::vector<char> bytes;
};

template <class T>
DataArray make_array(std::string name, std::string type, int components, const std::vector<T>& values) {
    DataArray a{std::move(name), std::move(type), components, std::vector<char>(values.size() * sizeof(T))};
    if (!values.empty()) std::memcpy(a.bytes.data(), values.data(), a.bytes.size());
    return a;
}

/// A one-tuple String array: \p text and its terminating NUL, as VTK stores strings.
DataArray string_array(std::string name, std::string_view text) {
    DataArray a{std::move(name), "String", 1, std::vector<char>(text.begin(), text.end())};
    a.bytes.push_back('\0');
    return a;
}

/// \p text with XML's special characters as entities, control characters as spaces.
std::string xml_escape(std::string_view text) {
    std::string out;
    for (const char c : text) {
        if (c == '&') out += "&amp;";
        else if (c == '<') out += "&lt;";
        else if (c == '>') out += "&gt;";
        else if (c == '"') out += "&quot;";
        else if (static_cast<unsigned char>(c) < 0x20) out += ' ';
        else out += c;
    }
    return out;
}

/// A dataset of one piece: an UnstructuredGrid (cells under <Cells>: connectivity, offsets,
/// types) or a PolyData (under <Polys>: connectivity, offsets).
struct Dataset {
    bool poly = false;
    std::int64_t points = 0, cells = 0;
    DataArray coordinates;
    std::vector<DataArray> topology, cell_data, field_data;
};

/// The tag of \p a with its offset \p offset in the appended block, advanced past it.
void put_array_tag(BufferedFile& out, const DataArray& a, bool field, std::uint64_t& offset) {
    out.put(a.type == "String" ? "        <Array type=\"" : "        <DataArray type=\"");
    out.put(a.type);
    out.put('"');
    if (!a.name.empty()) out.put(" Name=\"" + xml_escape(a.name) + '"');
    if (a.components != 1) out.put(" NumberOfComponents=\"" + std::to_string(a.components) + '"');
    if (field) out.put(" NumberOfTuples=\"1\"");
    out.put(" format=\"appended\" offset=\"");
    out.put(static_cast<std::int64_t>(offset));
    out.put("\"/>\n");
    offset += sizeof(std::uint64_t) + a.bytes.size();
}

void put_section(BufferedFile& out, std::string_view tag, const std::vector<DataArray>& arrays, bool field,
                 std::uint64_t& offset, std::string_view attributes = {}) {
    out.put("      <");
    out.put(tag);
    out.put(attributes);
    out.put(">\n");
    for (const DataArray& a : arrays) put_array_tag(out, a, field, offset);
    out.put("      </");
    out.put(tag);
    out.put(">\n");
}

/// \p d as a VTK XML file into \p temp (for \p target, named in errors).
void write_dataset(const Dataset& d, const std::string& temp, const std::string& target) {
    const std::string kind = d.poly ? "PolyData" : "UnstructuredGrid";
    BufferedFile out(temp, target);
    out.put("<?xml version=\"1.0\"?>\n<VTKFile type=\"" + kind +
            "\" version=\"1.0\" byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <" + kind + ">\n");
    std::uint64_t offset = 0;
    if (!d.field_data.empty()) put_section(out, "FieldData", d.field_data, true, offset);
    out.put("    <Piece NumberOfPoints=\"" + std::to_string(d.points) + "\" " +
            (d.poly ? "NumberOfVerts=\"0\" NumberOfLines=\"0\" NumberOfStrips=\"0\" NumberOfPolys=\""
                    : "NumberOfCells=\"") +
            std::to_string(d.cells) + "\">\n");
    put_section(out, "CellData", d.cell_data, false, offset);
    put_section(out, "Points", {d.coordinates}, false, offset);
    put_section(out, d.poly ? "Polys" : "Cells", d.topology, false, offset);
    out.put("    </Piece>\n  </" + kind + ">\n  <AppendedData encoding=\"raw\">\n   _");
    auto put_data = [&out](const DataArray& a) {
        const std::uint64_t size = a.bytes.size();
        out.put(std::string_view(reinterpret_cast<const char*>(&size), sizeof size));
        out.put(std::string_view(a.bytes.data(), a.bytes.size()));
    };
    for (const DataArray& a : d.field_data) put_data(a);
    for (const DataArray& a : d.cell_data) put_data(a);
    put_data(d.coordinates);
    for (const DataArray& a : d.topology) put_data(a);
    out.put("\n  </AppendedData>\n</VTKFile>\n");
    out.close();
}

/// The points \p ids of \p points (all of them if \p ids is null) as #points × 3 Float64.
DataArray coordinates(const std::vector<Vec3>& points, const std::vector<Index>* ids) {
    const std::size_t n = ids ? ids->size() : points.size();
    std::vector<double> xyz(3 * n);
    for (std::size_t i = 0; i < n; ++i) {
        const Vec3& p = points[ids ? static_cast<std::size_t>((*ids)[i]) : i];
        for (int k = 0; k < 3; ++k) xyz[3 * i + static_cast<std::size_t>(k)] = p[k];
    }
    return make_array("Points", "Float64", 3, xyz);
}

/// The volume's cells: connectivity (VTK's node order), offsets, types; the cell_type field.
void put_cells(const VolumeMesh& mesh, Dataset& d) {
    std::vector<std::int64_t> connectivity, offsets;
    std::vector<std::uint8_t> types;
    std::vector<std::int32_t> type_field;
    for (const CellType t : kCellTypes) {
        const int n = cell_corners(t);
        const std::uint8_t vtk = kVtkCellType[static_cast<std::size_t>(t)];
        for (std::size_t i = 0; i < mesh.num_cells(t); ++i) {
            const Index* c = mesh.cell(t, i);
            for (int k = 0; k < n; ++k) connectivity.push_back(c[t == CellType::Prism ? kWedgeOrder[static_cast<std::size_t>(k)] : k]);
            offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
            types.push_back(vtk);
            type_field.push_back(vtk);
        }
    }
    d.topology.push_back(make_array("connectivity", "Int64", 1, connectivity));
    d.topology.push_back(make_array("offsets", "Int64", 1, offsets));
    d.topology.push_back(make_array("types", "UInt8", 1, types));
    d.cell_data.push_back(make_array("cell_type", "Int32", 1, type_field));
}

/// The volume as an UnstructuredGrid with its cell fields (vtk_xml.h).
Dataset volume_dataset(const VolumeMesh& mesh, const std::string& path) {
    require_sound(check_volume_arrays(mesh), "cannot write '" + path + "': ");
    Dataset d;
    d.points = static_cast<std::int64_t>(mesh.points.size());
    d.cells = mesh.num_cells();
    d.coordinates = coordinates(mesh.points, nullptr);
    put_cells(mesh, d);
    std::vector<double> jacobian;
    jacobian.reserve(static_cast<std::size_t>(d.cells));
    for (const CellType t : kCellTypes)
        for (std::size_t i = 0; i < mesh.num_cells(t); ++i) jacobian.push_back(min_scaled_jacobian(mesh.points, mesh.cell(t, i), t));
    d.cell_data.push_back(make_array("scaled_jacobian", "Float64", 1, jacobian));
    const CellSolverFigures foam = cell_solver_figures(mesh, match_faces(mesh));
    d.cell_data.push_back(make_array("non_orthogonality", "Float64", 1, foam.non_orthogonality_deg));
    d.cell_data.push_back(make_array("skewness", "Float64", 1, foam.skewness));
    d.cell_data.push_back(make_array("aspect_ratio", "Float64", 1, foam.aspect_ratio));
    if (mesh.cell_layers.size() == static_cast<std::size_t>(d.cells))
        d.cell_data.push_back(make_array("layer", "Int32", 1, mesh.cell_layers));
    return d;
}

/// The faces of patch \p p as a PolyData over the points they use (ascending node ids);
/// \p local: #points entries of kNone, left so.
Dataset patch_dataset(const VolumeMesh& mesh, Index p, std::vector<Index>& local) {
    const SurfaceMesh& b = mesh.boundary;
    std::vector<Index> used;
    std::vector<std::int64_t> connectivity, offsets;
    for (Index f = 0; f < b.num_faces(); ++f) {
        if (b.face_patch[static_cast<std::size_t>(f)] != p) continue;
        for (const Index* v = b.face_begin(f); v != b.face_end(f); ++v) {
            if (local[static_cast<std::size_t>(*v)] == kNone) local[static_cast<std::size_t>(*v)] = 0, used.push_back(*v);
            connectivity.push_back(*v);
        }
        offsets.push_back(static_cast<std::int64_t>(connectivity.size()));
    }
    std::sort(used.begin(), used.end());
    for (std::size_t i = 0; i < used.size(); ++i) local[static_cast<std::size_t>(used[i])] = static_cast<Index>(i);
    for (std::int64_t& v : connectivity) v = local[static_cast<std::size_t>(v)];
    for (const Index v : used) local[static_cast<std::size_t>(v)] = kNone;
    Dataset d;
    d.poly = true;
    d.points = static_cast<std::int64_t>(used.size());
    d.cells = static_cast<std::int64_t>(offsets.size());
    d.coordinates = coordinates(mesh.points, &used);
    d.topology.push_back(make_array("connectivity", "Int64", 1, connectivity));
    d.topology.push_back(make_array("offsets", "Int64", 1, offsets));
    d.cell_data.push_back(make_array("patch", "Int32", 1, std::vector<std::int32_t>(offsets.size(), p)));
    const Patch& patch = b.patches[static_cast<std::size_t>(p)];
    d.field_data.push_back(string_array("patch_name", patch.name));
    d.field_data.push_back(string_array("patch_kind", to_string(patch.kind)));
    return d;
}

/// The last component of \p path.
std::string file_name(const std::string& path) {
    const std::size_t slash = path.rfind('/');
    return slash == std::string::npos ? path : path.substr(slash + 1);
}

}  // namespace

void write_vtu(const VolumeMesh& mesh, const std::string& path, Progress* progress, OutputSet* outputs) {
    report(progress, "writing", 0.0);
    const Dataset d = volume_dataset(mesh, path);
    report(progress, "writing", 0.5);
    OutputSet own;
    AtomicFile& file = (outputs ? *outputs : own).file(path);
    write_dataset(d, file.temp_path(), path);
    report(progress, "writing", 1.0);  // cancelled here: the temporary file goes, nothing is written
    if (!outputs) own.commit();
}

void write_vtm(const VolumeMesh& mesh, const std::string& path, Progress* progress, OutputSet* outputs) {
    report(progress, "writing", 0.0);
    const std::string dir = vtm_block_directory(path), rel = file_name(dir);
    const Dataset volume = volume_dataset(mesh, path);
    OutputSet own;
    OutputSet& set = outputs ? *outputs : own;
    AtomicFile& vtm = set.file(path);
    AtomicDirectory& blocks = set.directory(dir);
    write_dataset(volume, blocks.file("volume.vtu"), dir + "/volume.vtu");
    std::string xml = "<?xml version=\"1.0\"?>\n<VTKFile type=\"vtkMultiBlockDataSet\" version=\"1.0\" "
                      "byte_order=\"LittleEndian\" header_type=\"UInt64\">\n  <vtkMultiBlockDataSet>\n"
                      "    <DataSet index=\"0\" name=\"volume\" file=\"" + xml_escape(rel) + "/volume.vtu\"/>\n"
                      "    <Block index=\"1\" name=\"boundary\">\n";
    const SurfaceMesh& b = mesh.boundary;
    std::vector<char> has_faces(b.patches.size(), 0);
    for (const Index p : b.face_patch) has_faces[static_cast<std::size_t>(p)] = 1;
    std::vector<Index> local(mesh.points.size(), kNone);
    int block = 0;
    for (std::size_t p = 0; p < b.patches.size(); ++p) {
        if (!has_faces[p]) continue;
        report(progress, "writing", 0.5 + 0.5 * static_cast<double>(p) / static_cast<double>(b.patches.size()));
        const std::string name = std::to_string(p) + "_" + patch_word(b.patches[p].name, p) + ".vtp";
        write_dataset(patch_dataset(mesh, static_cast<Index>(p), local), blocks.file(name), dir + "/" + name);
        xml += "      <DataSet index=\"" + std::to_string(block++) + "\" name=\"" + xml_escape(b.patches[p].name) +
               "\" file=\"" + xml_escape(rel + "/" + name) + "\"/>\n";
    }
    xml += "    </Block>\n  </vtkMultiBlockDataSet>\n</VTKFile>\n";
    write_whole_file(vtm.temp_path(), path, xml);
    report(progress, "writing", 1.0);
    if (!outputs) own.commit();  // the .vtm and its directory together, or neither
}

}  // namespace strata
