#include "reports/finish_report.h"

#include <stdexcept>
#include <vector>

#include "core/output_file.h"
#include "reports/provenance.h"
#include "reports/report_json.h"
#include "reports/schema_validation.h"
#include "reports/summary_table.h"

namespace locbench::reports {
namespace {

Provenance stamped(const ReportTail& tail) {
  Provenance p = current_provenance(tail.command_line);
  p.threads = tail.threads;
  p.shards = tail.shards;
  return p;
}

void require_valid(const std::vector<std::string>& violations, const ReportTail& tail, const std::string& schema) {
  if (!violations.empty()) {
    throw std::logic_error(tail.producer + " produced a report that violates reports/" + schema + ": " +
                           violations.front());
  }
}

void say_wrote(const ReportTail& tail, std::ostream& log) {
  log << "wrote " << tail.path.string();
  if (!tail.wrote_detail.empty()) log << " (" << tail.wrote_detail << ')';
  log << '\n';
}

}  // namespace

void finish_report(Report& report, const ReportTail& tail, std::ostream& out, std::ostream& log) {
  report.provenance = stamped(tail);
  require_valid(validate_report_json(to_json(report)), tail, "report.schema.json");
  if (tail.print_summary) {
    out << summary_table({report});
    for (const MetricResult& r : report.body.results) {
      if (!r.note.empty()) out << r.name() << ": " << r.note << '\n';
    }
    for (const std::string& n : report.body.notes) out << n << '\n';
  }
  if (tail.path.empty()) return;
  write_report(report, tail.path);
  say_wrote(tail, log);
}

void finish_report(ShardReport& shard, const ReportTail& tail, std::ostream& log) {
  shard.provenance = stamped(tail);
  require_valid(validate_shard_json(to_json(shard)), tail, "shard.schema.json");
  if (tail.path.empty()) return;
  write_shard_report(shard, tail.path);
  say_wrote(tail, log);
}

void finish_report(nlohmann::json& diagnosis, const ReportTail& tail, std::ostream& log) {
  diagnosis["provenance"] = provenance_to_json(stamped(tail));
  require_valid(validate_diagnosis_json(diagnosis), tail, "diagnosis.schema.json");
  if (tail.path.empty()) return;
  write_file_atomically(tail.path, diagnosis.dump(2) + "\n");
  say_wrote(tail, log);
}

}  // namespace locbench::reports
