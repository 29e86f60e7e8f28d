// bspbench report: render a report as an HTML page with plots, by running analysis/report.py
// (cli/analysis_script.h says with which Python).
#include <filesystem>
#include <fstream>
#include <iostream>

#include "cli/analysis_script.h"
#include "cli/commands.h"
#include "common/errors.h"
#include "gate/regress.h"
#include "results/report.h"

namespace bsp::cli {

namespace {

namespace fs = std::filesystem;

// The gate's comparison of the two reports, for the page's "changes" section: written into the
// output directory (temporary file, then rename) so it is kept beside the page it explains.
std::string write_comparison(const std::string& baseline, const std::string& current, const std::string& out) {
  gate::RegressOptions options;
  options.match = gate::RunMatch::Command;  // a changed default parameter pairs its runs, not drops them
  const gate::RegressResult result =
      gate::compare_reports(results::read_report(baseline), results::read_report(current), options);
  return write_page_data(out, "comparison.json", gate::to_json(result));
}

int run(Args& args) {
  const std::string in = args.required("--in");
  const std::string out = args.required("--out");
  const auto baseline = args.option("--baseline");
  const auto format = args.option("--format");
  args.finish();
  if (format && *format != "csv" && *format != "markdown" && *format != "latex")
    throw UsageError("--format must be csv, markdown or latex, not '" + *format + "'");
  results::read_report(in);  // a bad report is reported here, in one line, not as a Python traceback
  std::vector<std::string> argv = {"--in", in, "--out", out};
  if (baseline) {
    const std::string comparison = write_comparison(*baseline, in, out);
    argv.insert(argv.end(), {"--baseline", *baseline, "--comparison", comparison});
  }
  if (format) argv.insert(argv.end(), {"--format", *format});
  const int status = run_analysis_script("report.py", argv);
  if (status == 0) std::cout << "report: wrote " << (fs::path(out) / "index.html").string() << "\n";
  return status == 0 ? 0 : status == 2 ? 2 : 1;
}

}  // namespace

Command report_command() {
  return {"report", "--in REPORT.json --out DIR [--baseline OLD.json] [--format csv|markdown|latex]",
          "render a sweep report as DIR/index.html with plots (runs analysis/report.py)", run,
          {{"--in REPORT.json", "a report of sweep or merge-reports"},
           {"--out DIR", "where index.html and its plots go"},
           {"--baseline OLD.json", "an earlier report of the same suite: the page opens with what changed, run group by "
                                   "run group, deterministic metrics exactly and timings with the regression gate's "
                                   "test (DIR/comparison.json keeps the gate's findings)"},
           {"--format F", "also export the verdict, cost-model, theory and metric tables as csv, markdown or latex "
                          "files into DIR/tables/"}}};
}

}  // namespace bsp::cli
