// The layer coverage report as JSON: write_report.h.

#include <strata/core/error.h>
#include <strata/core/format.h>
#include <strata/io/files.h>
#include <strata/io/write_report.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>

namespace strata {
namespace {

/// \p s as a JSON string literal.
std::string quoted(const std::string& s) {
    std::string out = "\"";
    for (const char c : s) {
        switch (c) {
            case '"':
                out += "\\\"";
                break;
            case '\\':
                out += "\\\\";
                break;
            case '\n':
                out += "\\n";
                break;
            case '\t':
                out += "\\t";
                break;
            default:
                if (static_cast<unsigned char>(c) < 0x20) {
                    char buf[8];
                    std::snprintf(buf, sizeof buf, "\\u%04x", static_cast<unsigned>(static_cast<unsigned char>(c)));
                    out += buf;
                } else {
                    out += c;
                }
        }
    }
    return out + "\"";
}

/// A finite number, or null (JSON has no infinity or NaN).
std::string number(double x) {
    return std::isfinite(x) ? format_number(x, 17) : "null";
}

}  // namespace

std::string report_path(const std::string& mesh_path) {
    // Beside an output directory (an OpenFOAM polyMesh), not in it: "polyMesh/" as "polyMesh".
    std::string p = mesh_path;
    while (p.size() > 1 && p.back() == '/') p.pop_back();
    return p + ".report.json";
}

void write_layer_report(const LayerReport& r, const std::string& path) {
    AtomicFile file(path);
    {
        std::ofstream out(file.temp_path());
        if (!out) throw InputError(path + ": cannot write the layer report; check the directory's permissions");
        out << "{\n  \"layers\": " << r.layers << ",\n  \"first_height\": " << number(r.first_height)
            << ",\n  \"thickness\": " << number(r.thickness) << ",\n  \"patches\": [";
        for (std::size_t i = 0; i < r.patches.size(); ++i) {
            const PatchCoverage& c = r.patches[i];
            out << (i ? ",\n" : "\n") << "    {\"name\": " << quoted(c.name) << ", \"faces\": " << c.faces
                << ", \"nodes\": " << c.nodes << ", \"full_nodes\": " << c.full_nodes
                << ", \"all_layers\": " << c.all_layers << ", \"mean_share\": " << number(c.mean_share)
                << ", \"min_share\": " << number(c.min_share) << ", \"mean_layers\": " << number(c.mean_layers)
                << ", \"min_layers\": " << c.min_layers << ", \"short\": {";
            for (std::size_t k = 1; k < kShortfalls; ++k)  // every reason but None, by name
                out << (k > 1 ? ", " : "") << quoted(std::string(to_string(static_cast<Shortfall>(k)))) << ": "
                    << c.short_by[k];
            out << "}}";
        }
        out << (r.patches.empty() ? "],\n" : "\n  ],\n") << "  \"short_nodes\": [";
        for (std::size_t i = 0; i < r.short_nodes.size(); ++i) {
            const ShortNode& n = r.short_nodes[i];
            out << (i ? ",\n" : "\n") << "    {\"node\": " << n.node << ", \"position\": [" << number(n.position.x())
                << ", " << number(n.position.y()) << ", " << number(n.position.z())
                << "], \"share\": " << number(n.share) << ", \"layers\": " << n.layers
                << ", \"reason\": " << quoted(std::string(to_string(n.reason))) << "}";
        }
        out << (r.short_nodes.empty() ? "],\n" : "\n  ],\n") << "  \"no_fan_nodes\": [";
        for (std::size_t i = 0; i < r.no_fan.size(); ++i) {
            const NoFanNode& n = r.no_fan[i];
            out << (i ? ",\n" : "\n") << "    {\"node\": " << n.node << ", \"position\": [" << number(n.position.x())
                << ", " << number(n.position.y()) << ", " << number(n.position.z())
                << "], \"reason\": " << quoted(std::string(to_string(n.reason))) << "}";
        }
        out << (r.no_fan.empty() ? "]\n}\n" : "\n  ]\n}\n");
        if (!out.flush()) throw InputError(path + ": writing the layer report failed (disk full?)");
    }
    file.commit();
}

}  // namespace strata
