// solshape: Sol's shapes seen from outside, written as meshes for figures,
// Blender, MeshLab or a 3D printer (docs/shapes.md).
//
//   solshape sphere --radius R [--center X,Y,Z] [--resolution N] [--size-mm S [--min-feature-mm T]] -o FILE.ply|.obj|.stl
//   solshape geodesics [--from X,Y,Z] --directions N --length L [--segments S] -o FILE.ply|.obj
//   solshape cut-locus [--center X,Y,Z] --radii R1,R2,... [--samples S] -o FILE.ply|.obj
//
// The meshes go through Assimp (Debian: libassimp-dev), which writes PLY,
// OBJ and (binary) STL from one in-memory scene; the file appears only when
// complete (sol::programs::OutputFile).
#include <assimp/Exporter.hpp>
#include <assimp/scene.h>
#include <glm/geometric.hpp>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <exception>
#include <filesystem>
#include <limits>
#include <numbers>
#include <vector>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>

#include <sol/error.hpp>
#include <sol/shapes.hpp>

#include "command_line.hpp"
#include "output_file.hpp"
#include "progress.hpp"

namespace {

// Assimp's exporter for a file name's extension: binary STL for printing,
// OBJ without a material file, ASCII PLY.
std::string format_of(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  if (ext == ".ply") return "ply";
  if (ext == ".obj") return "objnomtl";
  if (ext == ".stl") return "stlb";
  return "";
}

// Gives `scene` (whose destructor frees what is attached here) one mesh of
// `primitives`, with one default material, on its root node; returns it.
aiMesh& single_mesh(aiScene& scene, aiPrimitiveType primitives) {
  scene.mRootNode = new aiNode();
  scene.mMaterials = new aiMaterial*[1]{new aiMaterial()};
  scene.mNumMaterials = 1;
  scene.mMeshes = new aiMesh*[1]{new aiMesh()};
  scene.mNumMeshes = 1;
  scene.mRootNode->mMeshes = new unsigned int[1]{0};
  scene.mRootNode->mNumMeshes = 1;
  aiMesh& m = *scene.mMeshes[0];
  m.mMaterialIndex = 0;
  m.mPrimitiveTypes = primitives;
  return m;
}

// Writes `scene` into `file` in `format`: encoded by Assimp in memory,
// written with every write checked (Assimp's own file writes are not: a
// full disk left empty files); `what` names it in the error.
void export_scene(const aiScene& scene, const std::string& format, const sol::programs::OutputFile& file, const char* what) {
  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(&scene, format);
  if (!blob) throw std::runtime_error(std::string("cannot write the ") + what + ": " + exporter.GetErrorString());
  file.write(std::string_view(static_cast<const char*>(blob->data), blob->size));
}

// STL stores a normal per facet, which slicers may trust: Assimp's writer
// takes the mean of the facet's vertex normals (smoothed ones it makes when
// the mesh has none, up to 167 degrees from the facet's own on the strongly
// curved spheres of large radii). So each facet gets vertices of its own,
// with the facet's normal: the unit cross product of its edges, in the
// order of its vertices (outward, counter-clockwise).
void give_facet_normals(aiMesh& m) {
  const unsigned int faces = m.mNumFaces;
  auto* vertices = new aiVector3D[3 * static_cast<std::size_t>(faces)];
  auto* normals = new aiVector3D[3 * static_cast<std::size_t>(faces)];
  for (unsigned int i = 0; i < faces; ++i) {
    aiFace& f = m.mFaces[i];
    const glm::dvec3 a(m.mVertices[f.mIndices[0]].x, m.mVertices[f.mIndices[0]].y, m.mVertices[f.mIndices[0]].z);
    const glm::dvec3 b(m.mVertices[f.mIndices[1]].x, m.mVertices[f.mIndices[1]].y, m.mVertices[f.mIndices[1]].z);
    const glm::dvec3 c(m.mVertices[f.mIndices[2]].x, m.mVertices[f.mIndices[2]].y, m.mVertices[f.mIndices[2]].z);
    const glm::dvec3 cross = glm::cross(b - a, c - a);
    const double length = glm::length(cross);
    const glm::dvec3 n = length > 0.0 ? cross / length : glm::dvec3(0.0);
    for (unsigned int k = 0; k < 3; ++k) {
      vertices[3 * i + k] = m.mVertices[f.mIndices[k]];
      normals[3 * i + k] = aiVector3D(static_cast<ai_real>(n.x), static_cast<ai_real>(n.y), static_cast<ai_real>(n.z));
      f.mIndices[k] = 3 * i + k;
    }
  }
  delete[] m.mVertices;
  m.mVertices = vertices;
  m.mNormals = normals;
  m.mNumVertices = 3 * faces;
}

// Writes `mesh` (scaled by `scale`) to `path` in `format` through Assimp.
void write_mesh(const sol::Mesh& mesh, double scale, const std::string& format, const sol::programs::OutputFile& file) {
  aiScene scene;
  aiMesh& m = single_mesh(scene, aiPrimitiveType_TRIANGLE);
  m.mNumVertices = static_cast<unsigned int>(mesh.vertices.size());
  m.mVertices = new aiVector3D[mesh.vertices.size()];
  for (std::size_t i = 0; i < mesh.vertices.size(); ++i) {
    const glm::dvec3 v = scale * mesh.vertices[i];
    m.mVertices[i] = aiVector3D(static_cast<ai_real>(v.x), static_cast<ai_real>(v.y), static_cast<ai_real>(v.z));
    // The file holds floats: a point beyond their range is refused, never written as inf.
    const aiVector3D& f = m.mVertices[i];
    if (!std::isfinite(f.x) || !std::isfinite(f.y) || !std::isfinite(f.z)) {
      throw std::runtime_error("the mesh's points overflow the file's floats (--size-mm or the center is too large)");
    }
  }
  m.mNumFaces = static_cast<unsigned int>(mesh.triangles.size());
  m.mFaces = new aiFace[mesh.triangles.size()];
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) {
    aiFace& f = m.mFaces[i];
    f.mNumIndices = 3;
    f.mIndices = new unsigned int[3];
    for (int k = 0; k < 3; ++k) f.mIndices[k] = static_cast<unsigned int>(mesh.triangles[i][static_cast<std::size_t>(k)]);
  }
  if (format == "stlb") give_facet_normals(m);
  export_scene(scene, format, file, "mesh");
}

// Writes polylines as line segments (2-index faces: PLY faces of two
// vertices, OBJ `l` lines) through Assimp. STL has no lines.
void write_polylines(const std::vector<std::vector<glm::dvec3>>& lines, const std::string& format,
                     const sol::programs::OutputFile& file) {
  aiScene scene;
  aiMesh& m = single_mesh(scene, aiPrimitiveType_LINE);
  std::size_t points = 0, segments = 0;
  for (const auto& line : lines) {
    points += line.size();
    segments += line.empty() ? 0 : line.size() - 1;
  }
  m.mNumVertices = static_cast<unsigned int>(points);
  m.mVertices = new aiVector3D[points];
  m.mNumFaces = static_cast<unsigned int>(segments);
  m.mFaces = new aiFace[segments];
  std::size_t v = 0, f = 0;
  for (const auto& line : lines) {
    for (std::size_t i = 0; i < line.size(); ++i, ++v) {
      m.mVertices[v] = aiVector3D(static_cast<ai_real>(line[i].x), static_cast<ai_real>(line[i].y), static_cast<ai_real>(line[i].z));
      const aiVector3D& p = m.mVertices[v];
      if (!std::isfinite(p.x) || !std::isfinite(p.y) || !std::isfinite(p.z)) {
        throw std::runtime_error("the curves' points overflow the file's floats (the start is too far from the origin)");
      }
      if (i == 0) continue;
      aiFace& face = m.mFaces[f++];
      face.mNumIndices = 2;
      face.mIndices = new unsigned int[2]{static_cast<unsigned int>(v - 1), static_cast<unsigned int>(v)};
    }
  }
  export_scene(scene, format, file, "curves");
}

// The output checks shared by the curve commands: a known line format.
// Refuses an output that cannot be written as bad usage (exit 2), before
// any work: a directory, or a folder that does not exist.
void check_output(const sol::cli::CommandLine& cl, const std::string& output) {
  if (std::filesystem::is_directory(output)) cl.fail(output + ": cannot write: it is a directory");
  const std::filesystem::path folder = std::filesystem::path(output).parent_path();
  if (!folder.empty() && !std::filesystem::is_directory(folder)) {
    cl.fail(output + ": cannot write: the folder " + folder.string() + " does not exist");
  }
}

std::string curve_format(const sol::cli::CommandLine& cl, const std::string& output) {
  if (output.empty()) cl.fail("no output file: give -o FILE.ply|.obj");
  const std::string format = format_of(output);
  if (format.empty() || format == "stlb") cl.fail(output + ": unknown curve format (the name must end in .ply or .obj; STL holds no lines)");
  check_output(cl, output);
  return format;
}

// N directions spread evenly over the unit sphere (the Fibonacci lattice:
// equal areas in height, the golden angle around).
std::vector<glm::dvec3> spread_directions(int n) {
  std::vector<glm::dvec3> out;
  const double golden = std::numbers::pi * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double c = 1.0 - (2.0 * i + 1.0) / n, ring = std::sqrt(std::max(0.0, 1.0 - c * c));
    out.push_back({ring * std::cos(golden * i), ring * std::sin(golden * i), c});
  }
  return out;
}

int geodesics(int argc, char** argv) {
  sol::cli::CommandLine cl("solshape geodesics", "--directions N --length L [options] -o FILE.ply|.obj",
                           "Writes geodesics from a point as polylines in Sol coordinates (the paper's Fig. 2).");
  std::optional<glm::dvec3> from;
  int directions = 0, segments = 200;
  double length = 0.0;
  std::string output;
  cl.add_vec3("--from", from, "X,Y,Z", "where the geodesics start (default 0,0,0)");
  cl.add_integer("--directions", directions, 1, 100000, "N", "how many: N directions spread evenly over the sphere (Fibonacci lattice)");
  cl.add_number("--length", length, "L", "arc length of each geodesic (Sol units)", sol::cli::positive());
  cl.add_integer("--segments", segments, 1, 100000, "S", "segments per geodesic, evenly spaced in arc length (default 200)");
  cl.add_text("-o,--output", output, "FILE", "the curves: .ply (ASCII; segments as two-vertex faces) or .obj (l lines)");
  cl.set_footer("Points by the closed-form flow (sol::geodesic_polylines). docs/shapes.md.");
  cl.parse(argc, argv);
  if (directions == 0) cl.fail("--directions N is required");
  if (length == 0.0) cl.fail("--length L is required");
  // Before any work: the points the curves would hold (sol::kMaxPolylinePoints).
  if (static_cast<double>(directions) * (segments + 1.0) > sol::kMaxPolylinePoints) {
    char text[200];
    std::snprintf(text, sizeof text, "--directions %d x (--segments %d + 1) = %.3g points; at most %.0e (fewer directions or segments)",
                  directions, segments, static_cast<double>(directions) * (segments + 1.0), sol::kMaxPolylinePoints);
    cl.fail(text);
  }
  const std::string format = curve_format(cl, output);
  const auto lines = sol::geodesic_polylines(from.value_or(glm::dvec3(0.0)), spread_directions(directions), length, segments);
  sol::programs::OutputFile file(output);
  write_polylines(lines, format, file);
  file.commit();
  std::fprintf(stderr, "solshape: %d geodesics of length %g -> %s\n", directions, length, output.c_str());
  return 0;
}

int cut_locus(int argc, char** argv) {
  sol::cli::CommandLine cl("solshape cut-locus", "--radii R1,R2,... [options] -o FILE.ply|.obj",
                           "Writes the cut locus of a point as curves: where it meets the geodesic spheres of the given radii "
                           "(their creases), four arcs per radius.");
  std::optional<glm::dvec3> center;
  std::vector<double> radii;
  int samples = 64;
  std::string output;
  cl.add_vec3("--center", center, "X,Y,Z", "the point (default 0,0,0)");
  cl.add_value("--radii", "R1,R2,...", "radii in (sqrt(2) pi = 4.4429, 6]: one set of arcs each", [&](const std::string& text) {
    std::size_t start = 0;
    while (start <= text.size()) {
      const std::size_t comma = std::min(text.find(',', start), text.size());
      radii.push_back(cl.checked_number(text.substr(start, comma - start), "--radii",
                                        sol::cli::CommandLine::Condition{[](double r) { return r > sol::kSmoothSphereRadius && r <= sol::kMaxMeshedSphereRadius; },
                                                                         "in (sqrt(2) pi = 4.4429, 6]"}));
      start = comma + 1;
    }
  });
  cl.add_integer("--samples", samples, 2, 100000, "S", "points per arc (default 64)");
  cl.add_text("-o,--output", output, "FILE", "the curves: .ply (ASCII; segments as two-vertex faces) or .obj (l lines)");
  cl.set_footer("Every point has two minimising geodesics from the centre (sol::cut_locus_curves). docs/shapes.md.");
  cl.parse(argc, argv);
  if (radii.empty()) cl.fail("--radii R1,R2,... is required");
  if (static_cast<double>(radii.size()) * 4.0 * samples > sol::kMaxCutLocusPoints) {
    char text[200];
    std::snprintf(text, sizeof text, "%zu --radii x 4 arcs x --samples %d = %.3g points; at most %.0e (fewer radii or samples)",
                  radii.size(), samples, static_cast<double>(radii.size()) * 4.0 * samples, sol::kMaxCutLocusPoints);
    cl.fail(text);
  }
  const std::string format = curve_format(cl, output);
  const auto curves = sol::cut_locus_curves(center.value_or(glm::dvec3(0.0)), radii, samples);
  sol::programs::OutputFile file(output);
  write_polylines(curves, format, file);
  file.commit();
  std::fprintf(stderr, "solshape: cut locus at %zu radii, %zu arcs -> %s\n", radii.size(), curves.size(), output.c_str());
  return 0;
}

// The printability report of a mesh printed at `scale` millimetres per unit:
// the thinnest part (sol::vertex_thickness, looked for up to twice the
// least feature) and the share of vertices where it is thinner than that.
void report_printability(const sol::Mesh& mesh, double scale, double size_mm, double min_feature_mm) {
  const double reach_mm = 2.0 * min_feature_mm;
  // Progress on a terminal for a search that takes more than a second (a
  // fine mesh: a minute at --resolution 512), with the time left.
  const bool tty = isatty(fileno(stderr)) != 0;
  sol::programs::ProgressTimer timer;
  bool shown = false;
  const std::vector<double> thickness = sol::vertex_thickness(mesh, reach_mm / scale, [&](double fraction) {
    const std::optional<double> left = timer.report(fraction);
    if (!tty || (timer.seconds() < 1.0 && !shown)) return;
    shown = true;
    std::fprintf(stderr, "\rsolshape: printability: %3.0f %%", 100.0 * fraction);
    if (left && fraction < 1.0) std::fprintf(stderr, ", about %.0f s left", *left);
    std::fprintf(stderr, "        %s", fraction >= 1.0 ? "\n" : "");
  });
  double least = std::numeric_limits<double>::infinity();
  std::size_t at = 0, thin = 0;
  for (std::size_t k = 0; k < thickness.size(); ++k) {
    if (thickness[k] < least) {
      least = thickness[k];
      at = k;
    }
    thin += thickness[k] * scale < min_feature_mm;
  }
  if (!std::isfinite(least)) {
    std::fprintf(stderr, "solshape: printable at %g mm: no part is thinner than %g mm\n", size_mm, reach_mm);
    return;
  }
  const double least_mm = least * scale;
  const glm::dvec3 where = mesh.vertices[at] * scale;
  if (thin == 0) {
    std::fprintf(stderr, "solshape: printable at %g mm: the thinnest part is %.2f mm (at %.1f, %.1f, %.1f mm), above "
                 "--min-feature-mm %g\n", size_mm, least_mm, where.x, where.y, where.z, min_feature_mm);
    return;
  }
  std::fprintf(stderr,
               "solshape: warning: at %g mm the thinnest part is %.2f mm (at %.1f, %.1f, %.1f mm), and %.1f %% of the "
               "vertices lie where the mesh is thinner than --min-feature-mm %g: a printer may leave them out (print "
               "it larger, or a smaller radius)\n",
               size_mm, least_mm, where.x, where.y, where.z, 100.0 * static_cast<double>(thin) / static_cast<double>(thickness.size()),
               min_feature_mm);
}

int sphere(int argc, char** argv) {
  sol::cli::CommandLine cl("solshape sphere", "--radius R [options] -o FILE.ply|.obj|.stl",
                           "Writes a mesh of the geodesic sphere {p : d(center, p) = R} in Sol coordinates.");
  double radius = 0.0;
  std::optional<glm::dvec3> center;
  int resolution = 32;
  std::optional<double> size_mm, min_feature_mm;
  std::string output;
  cl.add_number("--radius", radius, "R",
                "the sphere's radius (Sol units), in (0, 6]; from sqrt(2) pi = 4.4429 on it meets the cut locus of "
                "its centre and has creases there",
                sol::cli::CommandLine::Condition{[](double r) { return r > 0.0 && r <= sol::kMaxMeshedSphereRadius; },
                                                 "in (0, 6]"});
  cl.add_vec3("--center", center, "X,Y,Z", "the centre (default 0,0,0)");
  cl.add_integer("--resolution", resolution, 1, 512, "N",
                 "each octant of directions in N^2 triangles: 8 N^2 triangles, 4 N^2 + 2 vertices, fewer beyond "
                 "sqrt(2) pi; at least 16 above radius 5.3 (default 32)");
  cl.add_number("--size-mm", size_mm, "S",
                "scale the mesh so that its largest extent is S millimetres (STL's unit, for printing); without "
                "it, coordinates are Sol units",
                sol::cli::positive());
  cl.add_number("--min-feature-mm", min_feature_mm, "T",
                "with --size-mm: the thinnest part a printer makes (default 0.8, a 0.4 mm nozzle's two lines); the "
                "printability report warns where the mesh is thinner",
                sol::cli::positive());
  cl.add_text("-o,--output", output, "FILE", "the mesh file: .ply (ASCII), .obj or .stl (binary)");
  cl.set_footer("Meshes are written with Assimp. With --size-mm a printability report follows: the thinnest part\n"
                "(the mesh's thickness along each vertex's inward normal) and how much is thinner than\n"
                "--min-feature-mm. docs/shapes.md has the construction and its accuracy.");
  cl.parse(argc, argv);
  if (radius == 0.0) cl.fail("--radius R is required");
  if (min_feature_mm && !size_mm) cl.fail("--min-feature-mm needs --size-mm (the mesh's size in millimetres)");
  // The report looks for thin parts up to twice the least feature: at most a
  // tenth of the print, so each vertex searches a small part of the mesh.
  if (min_feature_mm && *min_feature_mm > *size_mm / 20.0) {
    cl.fail("--min-feature-mm " + std::to_string(*min_feature_mm) + " must be at most --size-mm / 20 (" +
            std::to_string(*size_mm / 20.0) + ")");
  }
  if (output.empty()) cl.fail("no output file: give -o FILE.ply|.obj|.stl");
  const std::string format = format_of(output);
  if (format.empty()) cl.fail(output + ": unknown mesh format (the name must end in .ply, .obj or .stl)");
  check_output(cl, output);
  const sol::Mesh mesh = sol::geodesic_sphere(center.value_or(glm::dvec3(0.0)), radius, resolution);
  double scale = 1.0;
  if (size_mm) {
    glm::dvec3 lo(std::numeric_limits<double>::infinity()), hi(-std::numeric_limits<double>::infinity());
    for (const glm::dvec3& v : mesh.vertices) {
      lo = glm::min(lo, v);
      hi = glm::max(hi, v);
    }
    const glm::dvec3 extent = hi - lo;
    scale = *size_mm / std::max({extent.x, extent.y, extent.z});
  }
  sol::programs::OutputFile file(output);
  write_mesh(mesh, scale, format, file);
  file.commit();
  std::fprintf(stderr, "solshape: sphere of radius %g: %zu vertices, %zu triangles -> %s\n", radius, mesh.vertices.size(),
               mesh.triangles.size(), output.c_str());
  if (size_mm) report_printability(mesh, scale, *size_mm, min_feature_mm.value_or(0.8));
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  sol::programs::install_signal_cleanup();
  const std::string usage =
      "usage: solshape sphere --radius R [--center X,Y,Z] [--resolution N] [--size-mm S [--min-feature-mm T]] -o FILE.ply|.obj|.stl\n"
      "       solshape geodesics [--from X,Y,Z] --directions N --length L [--segments S] -o FILE.ply|.obj\n"
      "       solshape cut-locus [--center X,Y,Z] --radii R1,R2,... [--samples S] -o FILE.ply|.obj\n"
      "Writes Sol's shapes as meshes and curves (solshape COMMAND --help for the options).\n";
  if (argc < 2 || std::string(argv[1]) == "--help" || std::string(argv[1]) == "-h") {
    std::fputs(usage.c_str(), argc < 2 ? stderr : stdout);
    return argc < 2 ? 2 : 0;
  }
  const std::string shape = argv[1];
  try {
    if (shape == "sphere") return sphere(argc - 1, argv + 1);
    if (shape == "geodesics") return geodesics(argc - 1, argv + 1);
    if (shape == "cut-locus") return cut_locus(argc - 1, argv + 1);
    std::fprintf(stderr, "solshape: unknown shape '%s' (known: sphere, geodesics, cut-locus)\n", shape.c_str());
    return 2;
  } catch (const sol::InvalidArgument& e) {
    std::fprintf(stderr, "solshape: %s\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "solshape: %s\n", e.what());
    return 1;
  }
}
