#include "reports/schema_validation.h"

#include <valijson/adapters/nlohmann_json_adapter.hpp>
#include <valijson/schema.hpp>
#include <valijson/schema_parser.hpp>
#include <valijson/validator.hpp>

#include "diagnosis_schema.h"  // generated
#include "report_schema.h"     // generated
#include "shard_schema.h"      // generated

namespace locbench::reports {

namespace {

std::vector<std::string> validate(const nlohmann::json& schema_doc, const nlohmann::json& document) {
  valijson::Schema schema;
  valijson::SchemaParser parser;
  valijson::adapters::NlohmannJsonAdapter schema_adapter(schema_doc);
  parser.populateSchema(schema_adapter, schema);

  valijson::Validator validator(valijson::Validator::kStrongTypes);
  valijson::ValidationResults results;
  valijson::adapters::NlohmannJsonAdapter target(document);
  std::vector<std::string> errors;
  if (!validator.validate(schema, target, &results)) {
    valijson::ValidationResults::Error e;
    while (results.popError(e)) {
      std::string where;
      for (const std::string& c : e.context) where += c;
      errors.push_back(where + ": " + e.description);
    }
  }
  return errors;
}

}  // namespace

const char* report_schema_text() { return kReportSchemaJson; }
const char* shard_schema_text() { return kShardSchemaJson; }
const char* diagnosis_schema_text() { return kDiagnosisSchemaJson; }

std::vector<std::string> validate_report_json(const nlohmann::json& document) {
  static const nlohmann::json schema_doc = nlohmann::json::parse(kReportSchemaJson);
  return validate(schema_doc, document);
}

std::vector<std::string> validate_shard_json(const nlohmann::json& document) {
  static const nlohmann::json schema_doc = nlohmann::json::parse(kShardSchemaJson);
  return validate(schema_doc, document);
}

std::vector<std::string> validate_diagnosis_json(const nlohmann::json& document) {
  static const nlohmann::json schema_doc = nlohmann::json::parse(kDiagnosisSchemaJson);
  return validate(schema_doc, document);
}

}  // namespace locbench::reports
