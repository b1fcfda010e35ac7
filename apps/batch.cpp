// apps/batch.cpp: `skinmesh mesh IN IN ... -O DIR` (or --list) — many inputs
// meshed by --jobs workers, each as `skinmesh mesh` would mesh it alone, and
// a summary table, CSV and JSON of what became of each.
#include <nlohmann/json.hpp>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <map>
#include <mutex>
#include <thread>

#include "apps/mesh_command.h"
#include "apps/output.h"
#include "core/errors.h"
#include "core/read_file.h"
#include "geometry/mesh/mesh_measures.h"
#include "skin/atom_areas.h"
#include "skin/molecule_io.h"
#include "skin/skin_mesh_io.h"

namespace skinmesh::app {

namespace {

using json = nlohmann::ordered_json;

/// One input of a batch run and what became of it.
struct BatchItem {
  std::string input, output;
  int model = 0;           ///< --model all: the model read; 0: as --model says
  bool one_chain = false;  ///< --chains each: this item is the chain `chain`
  std::string chain;
  std::size_t atoms = 0, triangles = 0;
  double min_angle = 0, area = 0, volume = 0, seconds = 0;
  double skin_area = -1;  ///< --area-files: the exact skin's area, the sum of the atoms'; negative: not computed
  bool checked = false;
  int exit_code = -1;  ///< as `skinmesh mesh` on this input alone; -1: not run
  std::string status = "not run", message;
};

/// The inputs of a batch: the IN arguments, then the lines of --list (blank
/// lines and '#' comments skipped; relative paths are relative to the list's
/// folder). Throws InputError for an unreadable or empty list.
std::vector<std::string> batch_inputs(const MeshArgs& a) {
  std::vector<std::string> inputs = a.mol.inputs;
  if (!a.list.empty()) {
    const std::string text = read_file(a.list);
    const std::filesystem::path folder = std::filesystem::path(a.list).parent_path();
    std::size_t at = 0;
    while (at <= text.size()) {
      const std::size_t end = std::min(text.find('\n', at), text.size());
      std::string entry = text.substr(at, end - at);
      if (const std::size_t hash = entry.find('#'); hash != std::string::npos) entry.resize(hash);
      while (!entry.empty() && std::isspace(static_cast<unsigned char>(entry.back()))) entry.pop_back();
      std::size_t first = 0;
      while (first < entry.size() && std::isspace(static_cast<unsigned char>(entry[first]))) ++first;
      entry = entry.substr(first);
      if (!entry.empty()) {
        const std::filesystem::path p(entry);
        inputs.push_back(p.is_absolute() || folder.empty() ? entry : (folder / p).string());
      }
      at = end + 1;
    }
  }
  if (inputs.empty()) throw InputError(a.list, 0, "no molecule files listed");
  return inputs;
}

/// The output name of an input: its file name without .gz and its extension
/// (run_batch keeps the whole file name when two inputs share this name).
std::string batch_stem(const std::string& input) {
  std::filesystem::path p = std::filesystem::path(input).filename();
  if (p.extension() == ".gz" || p.extension() == ".GZ") p = p.stem();
  return p.stem().string();
}

/// The per-atom area file beside the mesh `output`: its name with .area for its extension.
std::string area_path(const std::string& output) {
  return std::filesystem::path(output).replace_extension(".area").string();
}

/// Meshes one input of a batch (never throws: the outcome is in the item).
void run_batch_item(const MeshArgs& a, const mesher::MeshOptions& base, BatchItem& item) {
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  try {
    MoleculeArgs m = a.mol;
    m.input = item.input;
    m.quiet = true;
    if (item.model != 0) m.model = std::to_string(item.model);
    if (item.one_chain) m.chains = item.chain;
    const skin::Molecule mol = load_molecule(m);
    item.atoms = mol.atoms.size();
    const mesher::MeshResult res = mesher::mesh_skin(mol, base);
    item.triangles = res.mesh.triangles.size();
    item.checked = res.checked;
    if (res.checked) item.min_angle = res.check.mesh.min_angle_deg;
    for (const geometry::ComponentMeasure& c : geometry::component_measures(res.mesh))
      item.area += c.area, item.volume += c.volume;
    if (!res.ok()) {
      item.exit_code = 3;
      item.status = "failed check";
      const std::vector<std::string> problems = res.problems();
      item.message = problems.empty() ? std::string() : problems.front();
      if (!a.force) {
        if (res.check.ok())
          item.message = stored_check_error(item.output, res);
        else
          item.message += " (not written; --force writes it)";
        item.seconds = std::chrono::duration<double>(Clock::now() - start).count();
        return;
      }
    }
    const skin::SkinMeshWriteOptions wopt = write_options(a, &mol);
    AtomAreas areas;
    if (a.area_files) areas = atom_areas(mol, res);
    skin::write_skin_mesh(item.output, res.mesh, res.vertex_data, wopt);
    if (a.area_files) {
      skin::write_area_file(area_path(item.output), areas.skin, areas.mesh, wopt.msms_atom_names);
      item.skin_area = 0;
      for (double x : areas.skin) item.skin_area += x;
    }
    if (item.exit_code == -1) item.exit_code = 0, item.status = "ok";
    if (!res.static_fallback.empty() && item.message.empty())
      item.message = res.static_fallback + "; meshed by the static baseline instead";
  } catch (const InputError& e) {
    item.exit_code = 1, item.status = "bad input", item.message = e.what();
  } catch (const TopologyError& e) {
    item.exit_code = 3, item.status = "topology error", item.message = e.what();
  } catch (const GeometryError& e) {
    item.exit_code = 3, item.status = "geometry error", item.message = e.what();
  } catch (const std::invalid_argument& e) {
    item.exit_code = 2, item.status = "bad option", item.message = e.what();
  } catch (const std::exception& e) {
    item.exit_code = 4, item.status = "internal error", item.message = e.what();
  }
  item.seconds = std::chrono::duration<double>(Clock::now() - start).count();
}

/// A CSV field, quoted if it needs to be (RFC 4180).
std::string csv_field(const std::string& s) {
  if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
  std::string q = "\"";
  for (char c : s) q += c == '"' ? std::string("\"\"") : std::string(1, c);
  return q + "\"";
}

}  // namespace

int run_batch(const MeshArgs& a) {
  if (a.out_dir.empty()) throw CLI::ValidationError("-O", "several inputs (or --list) need an output folder -O DIR");
  const std::vector<std::string> inputs = batch_inputs(a);
  // One item per input, or with --model all one per model of each input.
  std::vector<BatchItem> items;
  const auto item_of = [](const std::string& input, int model) {
    BatchItem item;
    item.input = input;
    item.model = model;
    return item;
  };
  skin::ReadOptions formats;
  for (const std::string& in : inputs) {
    std::vector<BatchItem> per_model;
    if (a.mol.model != "all") {
      per_model.push_back(item_of(in, 0));
    } else {
      try {
        if (!a.mol.format.empty()) formats.format = skin::format_from_extension("x." + a.mol.format);
        for (int model : skin::model_numbers(in, formats)) per_model.push_back(item_of(in, model));
      } catch (const InputError&) {
        per_model.push_back(item_of(in, 0));  // unreadable: it fails as an item, with the reader's message
      }
    }
    for (BatchItem& item : per_model) {
      if (a.mol.chains != "each") {
        items.push_back(item);
        continue;
      }
      // --chains each: the chains of this model (and assembly), one item each.
      try {
        MoleculeArgs m = a.mol;
        m.input = in;
        m.quiet = true;
        m.chains.clear();
        if (item.model != 0) m.model = std::to_string(item.model);
        for (const std::string& chain : skin::chain_names(load_molecule(m))) {
          BatchItem c = item;
          c.one_chain = true;
          c.chain = chain;
          items.push_back(c);
        }
      } catch (const InputError&) {
        items.push_back(item);
      }
    }
  }
  // Outputs DIR/NAME.FORMAT (DIR/NAME_modelN.FORMAT); inputs that share a NAME
  // (crambin.pdb and crambin.pqr) keep their whole file name (crambin.pdb.ply,
  // crambin.pqr.ply).
  std::map<std::string, int> stems;
  for (const std::string& in : inputs) ++stems[batch_stem(in)];
  std::map<std::string, std::string> taken;  // output -> input
  for (BatchItem& item : items) {
    const std::string stem = batch_stem(item.input);
    std::string name = stems[stem] > 1 ? std::filesystem::path(item.input).filename().string() : stem;
    if (item.model != 0) name += "_model" + std::to_string(item.model);
    if (item.one_chain) name += "_chain" + (item.chain.empty() ? std::string("_") : item.chain);
    item.output = (std::filesystem::path(a.out_dir) / (name + "." + a.batch_format)).string();
    if (auto [it, fresh] = taken.emplace(item.output, item.input); !fresh)
      throw InputError(item.input, 0, "would write " + item.output + " as " + it->second + " does (rename one)");
  }
  std::error_code made;
  std::filesystem::create_directories(a.out_dir, made);
  if (made) throw InputError(a.out_dir, 0, "cannot create the output folder (" + made.message() + ")");
  require_writable(items.front().output);
  mesher::MeshOptions base = mesh_options(a);
  if (!a.threads_given) base.threads = 1;  // the workers share the cores
  base.skin_atom_areas = a.area_files;
  base.stored_positions = skin::position_storage("mesh." + a.batch_format, write_options(a));
  using Clock = std::chrono::steady_clock;
  const auto start = Clock::now();
  std::atomic<std::size_t> next{0}, done{0};
  std::mutex print;
  const int jobs = std::max(1, std::min<int>(a.jobs, static_cast<int>(items.size())));
  auto worker = [&] {
    for (std::size_t i; (i = next.fetch_add(1)) < items.size();) {
      run_batch_item(a, base, items[i]);
      const std::size_t k = ++done;
      if (a.mol.quiet) continue;
      const BatchItem& it = items[i];
      std::lock_guard<std::mutex> lock(print);
      std::fprintf(stderr, "[%zu/%zu] %s%s%s: %s", k, items.size(), it.input.c_str(),
                   it.model ? (" model " + std::to_string(it.model)).c_str() : "",
                   it.one_chain ? (" chain " + it.chain).c_str() : "", it.status.c_str());
      if (it.exit_code == 0)
        std::fprintf(stderr, ", %zu triangles, min angle %.2f°, %.2f s", it.triangles, it.min_angle, it.seconds);
      if (!it.message.empty()) std::fprintf(stderr, ": %s", one_line(it.message).c_str());
      std::fprintf(stderr, "\n");
    }
  };
  std::vector<std::thread> pool;
  for (int j = 1; j < jobs; ++j) pool.emplace_back(worker);
  worker();
  for (std::thread& t : pool) t.join();
  const double wall = std::chrono::duration<double>(Clock::now() - start).count();

  // The summary: a table on stdout, CSV and JSON in the output folder.
  std::string table,
      csv = "input,model,chain,output,atoms,triangles,min_angle_deg,area_A2,volume_A3,seconds,status,message" +
            std::string(a.area_files ? ",skin_area_A2\n" : "\n");
  json rows = json::array();
  char line[512];
  std::snprintf(line, sizeof line, "%-36s %8s %10s %9s %8s  %s\n", "input", "atoms", "triangles", "min angle",
                "seconds", "status");
  table += line;
  int exit_code = 0;
  double sum = 0;
  for (const BatchItem& it : items) {
    const std::string name = std::filesystem::path(it.input).filename().string() +
                             (it.model ? " model " + std::to_string(it.model) : std::string()) +
                             (it.one_chain ? " chain " + it.chain : std::string());
    std::snprintf(line, sizeof line, "%-36s %8zu %10zu %9.3f %8.2f  %s\n", name.c_str(), it.atoms, it.triangles,
                  it.min_angle, it.seconds, it.status.c_str());
    table += line;
    char num[160];
    std::snprintf(num, sizeof num, ",%zu,%zu,%.6f,%.6f,%.6f,%.3f,", it.atoms, it.triangles, it.min_angle, it.area,
                  it.volume, it.seconds);
    const bool written = it.exit_code == 0 || (a.force && it.status == "failed check");
    csv += csv_field(it.input) + "," + (it.model ? std::to_string(it.model) : std::string()) + "," +
           (it.one_chain ? csv_field(it.chain) : std::string()) + "," + csv_field(written ? it.output : "") + num +
           csv_field(it.status) + "," + csv_field(one_line(it.message));
    if (a.area_files) {
      char skin_area[48] = "";
      if (it.skin_area >= 0) std::snprintf(skin_area, sizeof skin_area, "%.6f", it.skin_area);
      csv += std::string(",") + skin_area;
    }
    csv += "\n";
    json row = {{"input", it.input},         {"atoms", it.atoms},
                {"triangles", it.triangles}, {"min_angle_deg", it.min_angle},
                {"area_A2", it.area},        {"volume_A3", it.volume},
                {"seconds", it.seconds},     {"status", it.status},
                {"exit_code", it.exit_code}};
    if (it.model) row["model"] = it.model;
    if (it.one_chain) row["chain"] = it.chain;
    if (it.skin_area >= 0) row["skin_area_A2"] = it.skin_area, row["area_file"] = area_path(it.output);
    if (written) row["output"] = it.output;
    if (!it.message.empty()) row["message"] = it.message;
    rows.push_back(std::move(row));
    exit_code = std::max(exit_code, it.exit_code);
    sum += it.seconds;
  }
  const std::size_t failed = static_cast<std::size_t>(
      std::count_if(items.begin(), items.end(), [](const BatchItem& it) { return it.exit_code != 0; }));
  std::snprintf(line, sizeof line,
                "%zu inputs, %zu failed; wall %.2f s with %d jobs (sum of the inputs' times %.2f s)\n", items.size(),
                failed, wall, jobs, sum);
  table += line;
  std::cout << table << std::flush;
  const std::string csv_path = (std::filesystem::path(a.out_dir) / "summary.csv").string();
  const std::string json_path = (std::filesystem::path(a.out_dir) / "summary.json").string();
  write_text_file(csv_path, csv);
  write_text_file(
      json_path,
      json{
          {"inputs", std::move(rows)}, {"failed", failed}, {"jobs", jobs}, {"wall_seconds", wall}, {"sum_seconds", sum}}
              .dump(2, ' ', false, json::error_handler_t::replace) +
          "\n");
  if (!a.mol.quiet) std::cerr << "wrote " << csv_path << " and " << json_path << "\n";
  return exit_code;
}

}  // namespace skinmesh::app
