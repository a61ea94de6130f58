// drape_derive_builtin_materials: transcribes ArcSim's material files (the measured fabrics
// of Wang, O'Brien and Ramamoorthi 2011, see ../shared/materials/README.md) into the
// library's built-in table and into data/materials/ in Drape's own format:
//
//   cmake -S . -B build-tools -DDRAPE_BUILD_TOOLS=ON
//   cmake --build build-tools --target drape_derive_builtin_materials
//   build-tools/tools/drape_derive_builtin_materials cpp ../shared/materials > libcloth/src/builtin_materials.cpp
//   cmake --build build-tools --target drape_derive_builtin_materials   # embeds the new table
//   build-tools/tools/drape_derive_builtin_materials data data/materials
//
// `cpp` reads each ArcSim file with drape::cloth::load_material and prints the C++ table;
// `data` writes every built-in material with drape::cloth::save_material. So the numbers go
// ArcSim file -> double -> shortest round-trip decimal -> the same double at every step, and
// tests/cloth/test_material_format.cpp checks all three agree bit for bit.
#include <drape/cloth/material.hpp>
#include <drape/core/errors.hpp>

#include <nlohmann/json.hpp>

#include <cstdio>
#include <exception>
#include <filesystem>
#include <string>

namespace {

using drape::cloth::Material;

struct Fabric {
    const char* name;
    const char* description;
    bool measured;
};

// Garment type and fibre content from ArcSim's materials/README (SOURCE_README.txt); the
// paper and aluminium figures from the comments at the top of their files.
const Fabric kFabrics[] = {
    {"gray-interlock", "t-shirt fabric, 60% cotton 40% polyester (measured)", true},
    {"11oz-black-denim", "jeans fabric, 99% cotton 1% spandex (measured)", true},
    {"camel-ponte-roma", "jacket fabric, 60% polyester 40% rayon (measured)", true},
    {"ivory-rib-knit", "underwear fabric, 95% cotton 5% spandex (measured)", true},
    {"navy-sparkle-sweat", "sweater fabric, 96% polyester 4% spandex (measured)", true},
    {"pink-ribbon-brown", "blanket fabric, 100% polyester (measured)", true},
    {"royal-target", "pants fabric, 65% cotton 35% polyester (measured)", true},
    {"tango-red-jet-set", "jacket fabric, 100% polyester (measured)", true},
    {"white-dots-on-blk", "tablecloth fabric, 100% polyester (measured)", true},
    {"white-swim-solid", "swimsuit fabric, 87% nylon 13% spandex (measured)", true},
    {"paper",
     "not measured: ArcSim's hand-made isotropic sheet, thickness 0.1 mm, E = 5 GPa, "
     "stretching E h = 0.5 MN/m, bending E h^3/12 = 0.4 mN m",
     false},
    {"aluminium",
     "not measured: ArcSim's hand-made isotropic foil, thickness 25.4 um, E = 70 GPa, "
     "2.8 g/cm^3",
     false},
};

const char* const kWang2011 =
    "H. Wang, J. F. O'Brien, R. Ramamoorthi, \"Data-Driven Elastic Models for Cloth: Modeling "
    "and Measurement\", ACM Transactions on Graphics 30(4) (SIGGRAPH 2011), "
    "http://graphics.berkeley.edu/papers/Wang-DDE-2011-08/";
const char* const kArcSim =
    "ArcSim 0.3.1 (R. Narain, A. Samii, J. F. O'Brien, \"Adaptive Anisotropic Remeshing for "
    "Cloth Simulation\", ACM TOG 31(6), 2012)";

const char* const kLicense =
    "Research data: not for commercial use without a license. ArcSim's LICENSE: \"Copyright "
    "(c)2013 The Regents of the University of California (Regents). All Rights Reserved. "
    "Permission to use, copy, modify, and distribute this software and its documentation for "
    "educational, research, and not-for-profit purposes, without fee and without a signed "
    "licensing agreement, is hereby granted\", provided that the license text appears in all "
    "copies and that publications cite Narain, Samii, O'Brien 2012 and Narain, Pfaff, O'Brien "
    "2013; commercial licensing through UC Berkeley's Office of Technology Licensing. It adds: "
    "\"Contains code and data by Huamin Wang, Ravi Ramamoorthi, ... distributed with "
    "permission.\" Cite Wang, O'Brien, Ramamoorthi 2011 when using these numbers.";

std::string source_of(const Fabric& f) {
    const std::string file = std::string("materials/") + f.name + ".json";
    if (f.measured)
        return std::string(kWang2011) + "; as converted and shipped in " + kArcSim + ", " + file;
    return std::string("hand-made (not measured), shipped with the Wang et al. 2011 data in ") +
           kArcSim + ", " + file;
}

// A C++ string literal (the texts are ASCII; quotes and backslashes escaped), split into
// adjacent literals of at most ~80 characters at spaces, continued with `indent`.
std::string literal(const std::string& text, const std::string& indent) {
    std::string out = "\"";
    std::size_t run = 0;
    for (char c : text) {
        if (c == ' ' && run >= 72) {
            out += " \"\n" + indent + "\"";
            run = 0;
            continue;
        }
        if (c == '"' || c == '\\') out += '\\';
        out += c;
        ++run;
    }
    return out + "\"";
}

// `text` as `//` comment lines of at most ~92 characters.
std::string comment(const std::string& text) {
    std::string out = "//";
    std::size_t run = 2;
    std::size_t start = 0;
    while (start < text.size()) {
        std::size_t end = text.find(' ', start);
        if (end == std::string::npos) end = text.size();
        const std::string word = text.substr(start, end - start);
        if (run + 1 + word.size() > 92) {
            out += "\n//";
            run = 2;
        }
        out += " " + word;
        run += 1 + word.size();
        start = end + 1;
    }
    return out + "\n";
}

// Shortest decimal that reads back to the same double: a valid C++ double literal.
std::string number(double x) { return nlohmann::json(x).dump(); }

template <std::size_t R, std::size_t C>
void print_table(const std::array<std::array<double, C>, R>& t) {
    std::printf("     {{\n");
    for (std::size_t r = 0; r < R; ++r) {
        std::printf("         {");
        for (std::size_t c = 0; c < C; ++c)
            std::printf("%s%s", c ? ", " : "", number(t[r][c]).c_str());
        std::printf("}%s\n", r + 1 < R ? "," : "");
    }
    std::printf("     }},\n");
}

void print_cpp(const std::filesystem::path& dir) {
    std::printf(
        "// GENERATED by tools/derive_builtin_materials.cpp from ArcSim 0.3.1's materials/*.json;\n"
        "// do not edit (see docs/materials.md to regenerate).\n"
        "//\n"
        "%s"
        "// The numbers are ArcSim's conversion of the Wang et al. data, in our SI units\n"
        "// (density kg/m^2, stretching N/m, bending N m); \"paper\" and \"aluminium\" are ArcSim's\n"
        "// hand-made, unmeasured materials.\n"
        "//\n"
        "%s"
        "#include \"builtin_materials.hpp\"\n\n"
        "namespace drape::cloth::builtin {\n\n"
        "const char* const kLicense =\n    %s;\n\n"
        "const std::array<Entry, kCount> kMaterials = {{\n",
        comment(std::string("Measured cloth materials of ") + kWang2011 + ".").c_str(),
        comment(std::string("License notice: ") + kLicense).c_str(),
        literal(kLicense, "    ").c_str());
    for (const Fabric& f : kFabrics) {
        const Material m = drape::cloth::load_material(dir / (std::string(f.name) + ".json"));
        std::printf("    {%s,\n     %s,\n     %s,\n     %s,\n", literal(f.name, "     ").c_str(),
                    literal(f.description, "     ").c_str(),
                    literal(source_of(f), "     ").c_str(),
                    number(m.density_kg_per_m2).c_str());
        print_table(m.stretching_n_per_m);
        print_table(m.bending_n_m);
        std::printf("    },\n");
    }
    std::printf("}};\n\n}  // namespace drape::cloth::builtin\n");
}

void write_data(const std::filesystem::path& dir) {
    for (const std::string& name : drape::cloth::builtin_material_names())
        drape::cloth::save_material(drape::cloth::builtin_material(name), dir / (name + ".json"),
                                    drape::cloth::builtin_material_info(name));
}

}  // namespace

int main(int argc, char** argv) {
    const std::string usage =
        "usage: drape_derive_builtin_materials cpp ARCSIM_MATERIALS_DIR > builtin_materials.cpp\n"
        "       drape_derive_builtin_materials data OUTPUT_DIR\n";
    if (argc != 3) {
        std::fputs(usage.c_str(), stderr);
        return 2;
    }
    try {
        const std::string mode = argv[1];
        if (mode == "cpp") {
            print_cpp(argv[2]);
        } else if (mode == "data") {
            write_data(argv[2]);
        } else {
            std::fputs(usage.c_str(), stderr);
            return 2;
        }
    } catch (const std::exception& e) {
        std::fprintf(stderr, "error: %s\n", e.what());
        return 1;
    }
    return 0;
}
