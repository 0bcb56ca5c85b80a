// bench realtime's output: the frontier CSV (one row per integrator and target), the trials CSV
// (every trial, sorted by N within each search), both as JSON, a table on stdout and the plot of
// wall time per simulated second against N (bench/realtime.gp).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "bench/bench.h"
#include "bench/bench_realtime.h"

namespace cloth::app {
namespace {

using Json = nlohmann::json;

Json number(double x) {
    return std::isfinite(x) ? Json(x) : Json();
}

// Free text in a CSV cell: no separators, no line breaks.
std::string text(std::string s) {
    std::replace(s.begin(), s.end(), ',', ';');
    std::replace(s.begin(), s.end(), '\n', ' ');
    return s;
}

const std::vector<std::string> kFrontierColumns = {"method",
                                                   "target",
                                                   "backend",
                                                   "precision",
                                                   "n",
                                                   "vertices",
                                                   "dt_s",
                                                   "steps_per_frame",
                                                   "dt_halvings",
                                                   "predicted_tight_dt_s",
                                                   "wall_per_sim_s",
                                                   "next_n",
                                                   "next_status",
                                                   "next_wall_per_sim_s",
                                                   "pos_rms_err_rel",
                                                   "reference_dt_s",
                                                   "reference_change_rel",
                                                   "cg_iterations_per_step",
                                                   "cg_misses",
                                                   "trials",
                                                   "search_wall_s"};

const std::vector<std::string> kTrialColumns = {"method",
                                                "target",
                                                "backend",
                                                "precision",
                                                "n",
                                                "vertices",
                                                "dt_s",
                                                "steps_per_frame",
                                                "dt_halvings",
                                                "attempts",
                                                "predicted_tight_dt_s",
                                                "status",
                                                "simulated_s",
                                                "wall_s",
                                                "wall_per_sim_s",
                                                "cg_iterations_per_step",
                                                "cg_misses",
                                                "order",
                                                "reason"};

std::vector<std::string> targetCells(const Frontier& f) {
    return {methodName(f.method), f.target.id(), backendName(f.target.backend),
            precisionName(f.target.precision)};
}

std::vector<std::string> frontierCells(const Frontier& f) {
    std::vector<std::string> c = targetCells(f);
    const Trial none;
    const Trial& b = f.best >= 0 ? f.trials[std::size_t(f.best)] : none;
    const Trial* next = f.fail >= 0 ? &f.trials[std::size_t(f.fail)] : nullptr;
    const bool found = f.best >= 0;
    c.insert(c.end(),
             {std::to_string(b.n), std::to_string(long(b.n) * b.n), found ? cell(b.dt) : "",
              found ? std::to_string(b.stepsPerFrame) : "", found ? std::to_string(b.halvings) : "",
              cell(b.tightDt), cell(b.wallPerSim()), next ? std::to_string(next->n) : "",
              next ? trialStatusName(next->status) : "", next ? cell(next->wallPerSim()) : "",
              cell(f.error), cell(f.referenceDt), cell(f.referenceChange), cell(b.cgPerStep),
              found ? std::to_string(b.cgMisses) : "", std::to_string(f.trials.size()),
              cell(f.searchWall)});
    return c;
}

std::vector<std::string> trialCells(const Frontier& f, const Trial& t, std::size_t order) {
    std::vector<std::string> c = targetCells(f);
    c.insert(c.end(), {std::to_string(t.n), std::to_string(long(t.n) * t.n), cell(t.dt),
                       std::to_string(t.stepsPerFrame), std::to_string(t.halvings),
                       std::to_string(t.attempts), cell(t.tightDt), trialStatusName(t.status),
                       cell(t.simulated), cell(t.wall), cell(t.wallPerSim()), cell(t.cgPerStep),
                       std::to_string(t.cgMisses), std::to_string(order + 1), text(t.reason)});
    return c;
}

// Each search's trials by N (the plot's lines), with their order of running kept in a column.
std::vector<std::pair<std::size_t, std::size_t>> trialsByN(const std::vector<Frontier>& rows) {
    std::vector<std::pair<std::size_t, std::size_t>> order;  // (row, trial)
    for (std::size_t r = 0; r < rows.size(); ++r) {
        const auto first = order.size();
        for (std::size_t k = 0; k < rows[r].trials.size(); ++k) order.emplace_back(r, k);
        std::stable_sort(order.begin() + long(first), order.end(), [&](auto a, auto b) {
            return rows[r].trials[a.second].n < rows[r].trials[b.second].n;
        });
    }
    return order;
}

std::string header(const RealtimeMeta& m, const char* what) {
    char line[400];
    std::snprintf(line, sizeof line,
                  "# clothsim bench realtime (%s)%s: the drape, %s, %s form; T = %g s simulated "
                  "per trial; explicit dt = %g x tight bound; bisection to %g; reference "
                  "symplectic_euler cpu_double at min(tight bound; the rows' dt) / %g\n",
                  what, m.quick ? " (quick)" : "", m.materialLine.c_str(), m.form.c_str(), m.time,
                  m.safety, m.tolerance, m.referenceFactor);
    std::string s = line;
    if (!m.sets.empty()) s += "# --set " + join(m.sets, ' ') + "\n";
    s += "# build " + m.buildType + "; cpu " + m.cpuModel + "; gpu " +
         (m.gpuRenderer.empty() ? "none" : m.gpuRenderer) + "\n";
    s += "# units: n vertices per side; dt_s, predicted_tight_dt_s, reference_dt_s, simulated_s, "
         "wall_s, search_wall_s [s]; wall_per_sim_s wall seconds per simulated second (real "
         "time: <= 1); pos_rms_err_rel RMS over vertices of |x - x_ref| / the sheet's extent "
         "after T [1]; reference_change_rel the same between the reference and its run at "
         "twice its dt (the floor under which an error is not resolved) [1]; steps_per_frame per "
         "1/60 s\n";
    return s;
}

std::string frontierCsv(const RealtimeMeta& m, const std::vector<Frontier>& rows) {
    std::string s = header(m, "frontier") + join(kFrontierColumns, ',') + "\n";
    for (const Frontier& f : rows) s += join(frontierCells(f), ',') + "\n";
    return s;
}

std::string trialsCsv(const RealtimeMeta& m, const std::vector<Frontier>& rows) {
    std::string s = header(m, "trials") + join(kTrialColumns, ',') + "\n";
    for (const auto& [r, k] : trialsByN(rows))
        s += join(trialCells(rows[r], rows[r].trials[k], k), ',') + "\n";
    return s;
}

// A row as a JSON object: the cells by column, numbers as numbers.
Json object(const std::vector<std::string>& columns, const std::vector<std::string>& cells) {
    Json o;
    for (std::size_t i = 0; i < columns.size(); ++i) {
        const std::string& c = cells[i];
        char* end = nullptr;
        const double x = std::strtod(c.c_str(), &end);
        const bool numeric = !c.empty() && *end == '\0' && columns[i] != "order";
        o[columns[i]] = numeric ? number(x) : c.empty() ? Json() : Json(c);
    }
    return o;
}

std::string jsonText(const RealtimeMeta& m, const std::vector<Frontier>& rows) {
    Json j = {{"label", m.label},
              {"material", m.material},
              {"material_as_run", m.materialLine},
              {"sets", m.sets},
              {"form", m.form},
              {"simulated_s", m.time},
              {"safety", m.safety},
              {"tolerance", m.tolerance},
              {"reference_factor", m.referenceFactor},
              {"searched", m.searched},
              {"build_type", m.buildType},
              {"cpu_model", m.cpuModel},
              {"gpu_renderer", m.gpuRenderer},
              {"quick", m.quick},
              {"total_wall_s", number(m.totalWall)},
              {"frontier", Json::array()},
              {"trials", Json::array()}};
    for (const Frontier& f : rows)
        j["frontier"].push_back(object(kFrontierColumns, frontierCells(f)));
    for (const auto& [r, k] : trialsByN(rows))
        j["trials"].push_back(object(kTrialColumns, trialCells(rows[r], rows[r].trials[k], k)));
    return j.dump(2) + "\n";
}

void printTable(const RealtimeMeta& m, const std::vector<Frontier>& rows) {
    std::printf("\nreal-time frontier: the drape, %s (%s form), T = %g s%s%s | cpu %s | gpu %s\n",
                m.materialLine.c_str(), m.form.c_str(), m.time, m.sets.empty() ? "" : ", --set ",
                join(m.sets, ' ').c_str(), m.cpuModel.c_str(),
                m.gpuRenderer.empty() ? "none" : m.gpuRenderer.c_str());
    std::printf("%-16s %-10s %5s %10s %7s %4s %9s %-24s %9s %9s %6s\n", "method", "target", "N",
                "dt [s]", "st/frm", "halv", "wall/sim", "next N: status wall/sim", "error",
                "ref floor", "cg/st");
    for (const Frontier& f : rows) {
        char next[64] = "-";
        if (f.fail >= 0) {
            const Trial& t = f.trials[std::size_t(f.fail)];
            std::snprintf(next, sizeof next, "%d: %s %.3g", t.n, trialStatusName(t.status),
                          t.wallPerSim());
        }
        if (f.best < 0) {
            std::printf("%-16s %-10s %5s %10s %7s %4s %9s %-24s\n", methodName(f.method),
                        f.target.id().c_str(), "none", "-", "-", "-", "-", next);
            continue;
        }
        const Trial& b = f.trials[std::size_t(f.best)];
        std::printf("%-16s %-10s %5d %10.4g %7d %4d %9.3g %-24s %9.3g %9.3g %6.3g\n",
                    methodName(f.method), f.target.id().c_str(), b.n, b.dt, b.stepsPerFrame,
                    b.halvings, b.wallPerSim(), next, f.error, f.referenceChange, b.cgPerStep);
    }
    std::printf("whole run: %.1f s\n", m.totalWall);
}

}  // namespace

void reportRealtime(const std::string& outDir, const RealtimeMeta& meta,
                    const std::vector<Frontier>& rows) {
    const std::string stem = outputPath(outDir, "realtime_" + meta.label);
    writeWholeFile(stem + ".csv", frontierCsv(meta, rows));
    writeWholeFile(stem + "_trials.csv", trialsCsv(meta, rows));
    writeWholeFile(stem + ".json", jsonText(meta, rows));
    printTable(meta, rows);
    std::vector<std::pair<Method, BenchTarget>> curves;
    for (const Frontier& f : rows) curves.emplace_back(f.method, f.target);
    PlotVars vars = seriesVars(curves);
    vars.insert(vars.end(),
                {{"csv", stem + "_trials.csv"},
                 {"frontier_csv", stem + ".csv"},
                 {"title", "clothsim bench realtime: the drape, " + meta.material + " (" +
                               meta.form + " form), " + cell(meta.time) + " s simulated per trial"},
                 {"subtitle", meta.materialLine}});
    const auto plots = plot(meta.scriptDir, "realtime.gp", stem, vars);
    std::printf("wrote %s.csv, %s_trials.csv, %s.json", stem.c_str(), stem.c_str(), stem.c_str());
    for (const std::string& p : plots) std::printf(", %s", p.c_str());
    std::printf("\n");
}

}  // namespace cloth::app
