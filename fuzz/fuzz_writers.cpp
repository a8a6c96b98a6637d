// Fuzz target "writers": a small volume mesh decoded from the bytes (volume_soup.h) written as
// Cobalt60 (write_cobalt) and CGNS (write_cgns) into the scratch directory, over files already
// there, and read back: the Cobalt60 grid and its .bc map by the tests' independent reader
// (tests/io/cobalt_reader.h, which rebuilds the cells from the faces), the CGNS file with the
// CGNS library's own cg_* calls. Oracles: a file written holds the mesh (the nodes bit for bit,
// every cell with its faces, the boundary faces on their patches, the patches' names and kinds
// as each format documents them) and nothing else is left in the directory; a writer refuses
// (strata::Error) only a mesh whose arrays are unsound (check_volume_arrays) or, for Cobalt60,
// whose faces do not match (match_faces), and then leaves the files that were there untouched.
// Seeds: fuzz/corpus/writers/ (fuzz/make_seeds.py).

#include <strata/core/cell_faces.h>
#include <strata/core/error.h>
#include <strata/core/face_match.h>
#include <strata/core/mesh_check.h>
#include <strata/io/cgns.h>
#include <strata/io/cobalt.h>
#include <strata/io/files.h>

#include "cobalt_reader.h"
#include "fuzz_support.h"
#include "fuzz_targets.h"
#include "volume_soup.h"

#include <cgnslib.h>

#include <algorithm>
#include <array>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace strata::fuzz {
namespace {

namespace fs = std::filesystem;

/// What a file holds before a write: a refused write must leave it so.
constexpr const char* kPrevious = "the previous output\n";

bool same_bits(double a, double b) {
    return std::memcmp(&a, &b, sizeof a) == 0;
}

bool same_points(const std::vector<Vec3>& a, const std::vector<Vec3>& b) {
    if (a.size() != b.size()) return false;
    for (std::size_t i = 0; i < a.size(); ++i)
        for (int d = 0; d < 3; ++d)
            if (!same_bits(a[i][d], b[i][d])) return false;
    return true;
}

/// A face from its first smallest node on, so that two listings of one oriented face compare equal.
std::vector<Index> rotated(std::vector<Index> f) {
    std::rotate(f.begin(), std::min_element(f.begin(), f.end()), f.end());
    return f;
}

/// The faces of a cell, each outward as its corners give it (cell_faces), rotated and sorted:
/// equal for two corner lists exactly when they make the same cell.
std::vector<std::vector<Index>> cell_shape(CellType t, const Index* v) {
    const CellFaceTable& table = cell_faces(t);
    std::vector<std::vector<Index>> faces;
    for (std::size_t k = 0; k < static_cast<std::size_t>(table.count); ++k) {
        std::vector<Index> f;
        for (std::size_t j = 0; j < static_cast<std::size_t>(table.size[k]); ++j) f.push_back(v[table.node[k][j]]);
        faces.push_back(rotated(f));
    }
    std::sort(faces.begin(), faces.end());
    return faces;
}

/// Every cell has distinct corners (a cell that repeats one cannot be rebuilt from its faces).
bool distinct_corners(const VolumeMesh& m) {
    for (CellType t : kCellTypes)
        for (std::size_t i = 0; i < m.num_cells(t); ++i) {
            std::vector<Index> v(m.cell(t, i), m.cell(t, i) + cell_corners(t));
            std::sort(v.begin(), v.end());
            if (std::adjacent_find(v.begin(), v.end()) != v.end()) return false;
        }
    return true;
}

/// The boundary faces as (rotated face, patch number), sorted; \p number maps a patch index.
template <class Number>
std::vector<std::pair<std::vector<Index>, std::int64_t>> boundary_faces(const SurfaceMesh& b, Number&& number) {
    std::vector<std::pair<std::vector<Index>, std::int64_t>> out;
    for (Index f = 0; f < b.num_faces(); ++f)
        out.emplace_back(rotated({b.face_begin(f), b.face_end(f)}), number(b.face_patch[f]));
    std::sort(out.begin(), out.end());
    return out;
}

/// A patch's name as the .bc file gives it back (cobalt.h's format, one line "<number> <name>
/// <kind>"): control characters '_', no blanks at the ends, "patch_<number>" if blank.
std::string cobalt_name(std::string name, std::int64_t number) {
    for (char& c : name)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '_';
    const std::size_t b = name.find_first_not_of(' ');
    if (b == std::string::npos) return "patch_" + std::to_string(number);
    return name.substr(b, name.find_last_not_of(' ') - b + 1);
}

/// The Cobalt60 grid at \p path and its .bc map hold \p m.
void check_cobalt(const VolumeMesh& m, const std::string& path) {
    const test::CobaltGrid g = test::read_cobalt(path);
    const std::vector<test::CobaltPatch> bc = test::read_cobalt_bc(path + ".bc");
    require(g.ndim == 3 && g.nzones == 1 && g.ncells == m.num_cells(), "the Cobalt60 header counts the cells");
    require(same_points(g.points, m.points), "the Cobalt60 grid holds the nodes bit for bit");
    // Patches numbered 1.. over those with faces, in patch-table order.
    const SurfaceMesh& b = m.boundary;
    std::vector<std::int64_t> number(b.patches.size(), 0);
    for (Index p : b.face_patch) number[static_cast<std::size_t>(p)] = 1;
    std::int64_t numbered = 0;
    for (std::size_t p = 0; p < b.patches.size(); ++p) {
        if (number[p] == 0) continue;
        number[p] = ++numbered;
        const auto at = static_cast<std::size_t>(numbered - 1);
        require(at < bc.size() && bc[at].number == numbered &&
                    bc[at].name == cobalt_name(b.patches[p].name, numbered) &&
                    bc[at].kind == to_string(b.patches[p].kind),
                "the .bc map names patch " + std::to_string(p) + " '" + b.patches[p].name + "'");
    }
    require(g.npatches == numbered && bc.size() == static_cast<std::size_t>(numbered),
            "the Cobalt60 grid and its .bc map count the patches with faces");
    if (!distinct_corners(m)) return;
    const test::RebuiltMesh r = test::rebuild_mesh(g, bc);
    for (CellType t : kCellTypes) {
        require(r.mesh.num_cells(t) == m.num_cells(t), "the Cobalt60 grid has every " + std::string(to_string(t)));
        for (std::size_t i = 0; i < m.num_cells(t); ++i)
            require(cell_shape(t, r.mesh.cell(t, i)) == cell_shape(t, m.cell(t, i)),
                    "the Cobalt60 grid's faces make " + std::string(to_string(t)) + " " + std::to_string(i));
    }
    require(boundary_faces(r.mesh.boundary, [&](Index p) { return bc[static_cast<std::size_t>(p)].number; }) ==
                boundary_faces(b, [&](Index p) { return number[static_cast<std::size_t>(p)]; }),
            "the Cobalt60 grid's boundary faces are the mesh's, on their patches");
}

/// A CGNS call's status: anything but CG_OK is a finding (the file was written by write_cgns).
void cg(int status, const char* call) {
    if (status != CG_OK) require(false, std::string("reading the CGNS file back: ") + call + ": " + cg_get_error());
}

/// A CGNS file open for reading, closed on every path.
class CgnsRead {
public:
    explicit CgnsRead(const std::string& path) { cg(cg_open(path.c_str(), CG_MODE_READ, &fn_), "cg_open"); }
    ~CgnsRead() { cg_close(fn_); }
    CgnsRead(const CgnsRead&) = delete;
    CgnsRead& operator=(const CgnsRead&) = delete;
    int fn() const { return fn_; }

private:
    int fn_ = -1;
};

struct Section {
    CGNS_ENUMT(ElementType_t) type;
    cgsize_t start = 0, end = 0;
    std::vector<cgsize_t> conn;
};

/// A patch's sections: \p count (0-2) from number \p first on (0-based).
struct PatchSections {
    std::size_t first = 0, count = 0;
};

/// Every section of zone 1 of base 1, by number, with its name.
std::vector<std::pair<std::string, Section>> read_sections(int fn) {
    int count = 0;
    cg(cg_nsections(fn, 1, 1, &count), "cg_nsections");
    std::vector<std::pair<std::string, Section>> out;
    for (int s = 1; s <= count; ++s) {
        char name[64] = {};
        Section sec;
        int nbndry = 0, parent = 0;
        cg(cg_section_read(fn, 1, 1, s, name, &sec.type, &sec.start, &sec.end, &nbndry, &parent), "cg_section_read");
        cgsize_t size = 0;
        cg(cg_ElementDataSize(fn, 1, 1, s, &size), "cg_ElementDataSize");
        sec.conn.resize(static_cast<std::size_t>(size));
        if (size > 0) cg(cg_elements_read(fn, 1, 1, s, sec.conn.data(), nullptr), "cg_elements_read");
        out.emplace_back(name, std::move(sec));
    }
    return out;
}

/// What cgns.h says the sections are: one per cell type present, then per patch with faces its
/// triangles and its quadrilaterals (1-based nodes), numbered on from 1; each patch's sections
/// in \p of_patch.
std::vector<Section> expected_sections(const VolumeMesh& m, std::vector<PatchSections>& of_patch) {
    constexpr std::array<CGNS_ENUMT(ElementType_t), 4> kTypes{CGNS_ENUMV(TETRA_4), CGNS_ENUMV(PYRA_5),
                                                              CGNS_ENUMV(PENTA_6), CGNS_ENUMV(HEXA_8)};
    std::vector<Section> out;
    cgsize_t next = 1;
    auto add = [&](CGNS_ENUMT(ElementType_t) type, cgsize_t count, std::vector<cgsize_t> conn) {
        if (count == 0) return;
        out.push_back({type, next, next + count - 1, std::move(conn)});
        next += count;
    };
    for (CellType t : kCellTypes) {
        std::vector<cgsize_t> conn;
        for (std::size_t i = 0; i < m.num_cells(t); ++i)
            for (int k = 0; k < cell_corners(t); ++k) conn.push_back(static_cast<cgsize_t>(m.cell(t, i)[k]) + 1);
        add(kTypes[static_cast<std::size_t>(t)], static_cast<cgsize_t>(m.num_cells(t)), std::move(conn));
    }
    const SurfaceMesh& b = m.boundary;
    for (std::size_t p = 0; p < b.patches.size(); ++p) {
        std::array<std::vector<cgsize_t>, 2> conn;  // triangles, quadrilaterals
        for (Index f = 0; f < b.num_faces(); ++f)
            if (b.face_patch[f] == static_cast<Index>(p))
                for (const Index* v = b.face_begin(f); v != b.face_end(f); ++v)
                    conn[b.face_size(f) == 4].push_back(static_cast<cgsize_t>(*v) + 1);
        const std::size_t before = out.size();
        const auto nt = static_cast<cgsize_t>(conn[0].size() / 3), nq = static_cast<cgsize_t>(conn[1].size() / 4);
        add(CGNS_ENUMV(TRI_3), nt, std::move(conn[0]));
        add(CGNS_ENUMV(QUAD_4), nq, std::move(conn[1]));
        of_patch.push_back({before, out.size() - before});
    }
    return out;
}

/// The boundary condition each patch kind must get, in PatchKind's order (wall, symmetry,
/// farfield, other).
constexpr std::array<CGNS_ENUMT(BCType_t), 4> kExpectedBc{CGNS_ENUMV(BCWall), CGNS_ENUMV(BCSymmetryPlane),
                                                          CGNS_ENUMV(BCFarfield), CGNS_ENUMV(BCTypeUserDefined)};

/// Per patch with faces, in patch order, a boundary condition named as its first section, over
/// its elements (PointRange, FaceCenter), of its kind's BC type (cgns.h), with a family of that
/// name at the base carrying the same type.
void check_cgns_patches(const VolumeMesh& m, int fn, const std::vector<std::pair<std::string, Section>>& sections,
                        const std::vector<PatchSections>& of_patch) {
    int nbocos = 0, nfamilies = 0;
    cg(cg_nbocos(fn, 1, 1, &nbocos), "cg_nbocos");
    cg(cg_nfamilies(fn, 1, &nfamilies), "cg_nfamilies");
    std::map<std::string, CGNS_ENUMT(BCType_t)> family_bc;
    for (int f = 1; f <= nfamilies; ++f) {
        char name[64] = {}, fambc[64] = {};
        int nfambc = 0, ngeos = 0;
        CGNS_ENUMT(BCType_t) type;
        cg(cg_family_read(fn, 1, f, name, &nfambc, &ngeos), "cg_family_read");
        require(nfambc == 1, std::string("CGNS family '") + name + "' carries a BC type");
        cg(cg_fambc_read(fn, 1, f, 1, fambc, &type), "cg_fambc_read");
        family_bc[name] = type;
    }
    // The patches' names as cgns.h says (cgns_names), kept apart from the names of the zone's and
    // the base's other children.
    std::vector<std::string> patch_names;
    for (const Patch& patch : m.boundary.patches) patch_names.push_back(patch.name);
    patch_names = cgns_names(patch_names, {"Fluid", "GridCoordinates", "ZoneBC", "ZoneType", "FamilyName", "Tetrahedra",
                                           "Pyramids", "Prisms", "Hexahedra"});
    int bc = 0;
    for (std::size_t p = 0; p < of_patch.size(); ++p) {
        if (of_patch[p].count == 0) continue;
        const std::string what = "the CGNS boundary condition of patch " + std::to_string(p);
        require(++bc <= nbocos, what + " is there");
        const std::string& section = sections[of_patch[p].first].first;
        require(section == patch_names[p], what + " is named '" + patch_names[p] + "', not '" + section + "'");
        const std::array<cgsize_t, 2> range{sections[of_patch[p].first].second.start,
                                            sections[of_patch[p].first + of_patch[p].count - 1].second.end};
        char name[64] = {}, family[64] = {};
        CGNS_ENUMT(BCType_t) type;
        CGNS_ENUMT(PointSetType_t) ptset;
        CGNS_ENUMT(DataType_t) normal_type;
        CGNS_ENUMT(GridLocation_t) location;
        cgsize_t npnts = 0, normal_size = 0;
        int normal_index[3] = {}, ndataset = 0;
        cg(cg_boco_info(fn, 1, 1, bc, name, &type, &ptset, &npnts, normal_index, &normal_size, &normal_type, &ndataset),
           "cg_boco_info");
        require(name == section && type == kExpectedBc[static_cast<std::size_t>(m.boundary.patches[p].kind)] &&
                    ptset == CGNS_ENUMV(PointRange) && npnts == 2,
                what + " is named as its section, of its kind, a point range");
        std::array<cgsize_t, 2> got{};
        cg(cg_boco_read(fn, 1, 1, bc, got.data(), nullptr), "cg_boco_read");
        cg(cg_boco_gridlocation_read(fn, 1, 1, bc, &location), "cg_boco_gridlocation_read");
        cg(cg_goto(fn, 1, "Zone_t", 1, "ZoneBC_t", 1, "BC_t", bc, "end"), "cg_goto");
        cg(cg_famname_read(family), "cg_famname_read");
        require(got == range && location == CGNS_ENUMV(FaceCenter) && name == std::string(family) &&
                    family_bc.count(family) && family_bc[family] == type,
                what + " spans its elements at face centres, with its family");
    }
    require(bc == nbocos && nfamilies == bc,
            "the CGNS file has a boundary condition and a family per patch with faces");
}

/// The CGNS file at \p path holds \p m: the zone's sizes, the coordinates bit for bit, the
/// sections, and per patch with faces a boundary condition over its elements named as its first
/// section, with a family of that name carrying the same BC type.
void check_cgns(const VolumeMesh& m, const std::string& path) {
    const CgnsRead file(path);
    const int fn = file.fn();
    int nbases = 0, nzones = 0, cell_dim = 0, phys_dim = 0;
    char name[64] = {};
    cg(cg_nbases(fn, &nbases), "cg_nbases");
    cg(cg_base_read(fn, 1, name, &cell_dim, &phys_dim), "cg_base_read");
    cg(cg_nzones(fn, 1, &nzones), "cg_nzones");
    std::array<cgsize_t, 3> size{};
    cg(cg_zone_read(fn, 1, 1, name, size.data()), "cg_zone_read");
    require(nbases == 1 && cell_dim == 3 && phys_dim == 3 && nzones == 1 &&
                size == std::array<cgsize_t, 3>{static_cast<cgsize_t>(m.points.size()), m.num_cells(), 0},
            "the CGNS file has one base and one zone of the mesh's size");
    std::vector<double> x(m.points.size());
    cgsize_t lo = 1, hi = static_cast<cgsize_t>(m.points.size());
    for (int d = 0; d < 3; ++d) {
        constexpr std::array<const char*, 3> kCoord{"CoordinateX", "CoordinateY", "CoordinateZ"};
        cg(cg_coord_read(fn, 1, 1, kCoord[static_cast<std::size_t>(d)], CGNS_ENUMV(RealDouble), &lo, &hi, x.data()),
           "cg_coord_read");
        for (std::size_t i = 0; i < x.size(); ++i)
            require(same_bits(x[i], m.points[i][d]), "the CGNS file holds the nodes bit for bit");
    }
    std::vector<PatchSections> of_patch;
    const std::vector<Section> want = expected_sections(m, of_patch);
    const std::vector<std::pair<std::string, Section>> got = read_sections(fn);
    require(got.size() == want.size(), "the CGNS file has a section per cell type and per patch's face type");
    std::set<std::string> names;
    for (std::size_t s = 0; s < want.size(); ++s) {
        const Section& g = got[s].second;
        require(g.type == want[s].type && g.start == want[s].start && g.end == want[s].end && g.conn == want[s].conn,
                "CGNS section " + std::to_string(s + 1) + " '" + got[s].first + "' holds its elements");
        require(names.insert(got[s].first).second && got[s].first.size() <= 32 &&
                    got[s].first.find('/') == std::string::npos,
                "CGNS section names are unique, CGNS names");
    }
    check_cgns_patches(m, fn, got, of_patch);
}

/// The names in \p dir, sorted.
std::vector<std::string> entries(const fs::path& dir) {
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
    std::sort(names.begin(), names.end());
    return names;
}

/// One writer over \p files (its output first, then its companions, sorted), each holding
/// kPrevious beforehand in an otherwise empty directory: it writes them all and nothing else,
/// and \p check reads them back; or it refuses with strata::Error, only if not \p writable, and
/// leaves them as they were.
template <class Write, class Check>
void round_trip(const std::string& format, const std::vector<std::string>& files, bool writable, Write&& write,
                Check&& check) {
    const fs::path dir = scratch_path("writers");
    fs::remove_all(dir);
    fs::create_directory(dir);
    for (const std::string& f : files) std::ofstream(dir / f, std::ios::binary) << kPrevious;
    const std::string path = (dir / files[0]).string();
    std::string refusal;
    try {
        write(path);
    } catch (const Error& e) {
        refusal = e.what();
    }
    require(entries(dir) == files, format + ": the directory holds the output and nothing else");
    if (!refusal.empty()) {
        require(!writable, format + " refuses a mesh it can write: " + refusal);
        for (const std::string& f : files)
            require(read_whole_file((dir / f).string()) == kPrevious, format + ": a refused write leaves " + f);
        return;
    }
    require(writable, format + " writes a mesh with unsound arrays or unmatched faces");
    check(path);
}

}  // namespace
}  // namespace strata::fuzz

int strata_fuzz_one_writers(const std::uint8_t* data, std::size_t size) {
    using namespace strata;
    const VolumeMesh mesh = fuzz::decode_volume(data, size);
    // What the writers may refuse: unsound arrays (both), faces that do not match (Cobalt60's face list).
    const bool sound = check_volume_arrays(mesh).ok();
    const bool matched = sound && match_faces(mesh).ok();
    fuzz::round_trip(
        "Cobalt60", {"mesh.cgr", "mesh.cgr.bc"}, matched, [&](const std::string& path) { write_cobalt(mesh, path); },
        [&](const std::string& path) { fuzz::check_cobalt(mesh, path); });
    fuzz::round_trip(
        "CGNS", {"mesh.cgns"}, sound, [&](const std::string& path) { write_cgns(mesh, path); },
        [&](const std::string& path) { fuzz::check_cgns(mesh, path); });
    return 0;
}

#ifdef STRATA_LIBFUZZER
extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    return strata_fuzz_one_writers(data, size);
}
#endif
