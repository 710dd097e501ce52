#ifndef vimlop_RecordJson_h
#define vimlop_RecordJson_h

// JSON forms shared by the result folder (RegistrationRecordIO) and the
// report (RegistrationReport, in the Report module): not installed, so they
// stay free to change with result.json.

#include <vimlop/Core/RegistrationOptions.h>
#include <vimlop/Core/SimilarityTransform.h>
#include <vimlop/Results/RegistrationRecord.h>

#include <nlohmann/json.hpp>

#include <Eigen/Core>

#include <string>

namespace vimlop::recordjson
{

using json = nlohmann::json;

/// A matrix as a list of rows.
json matrixJson(const Eigen::MatrixXd& m);
/// An n x n matrix from a list of rows. @throws vimlop::Error naming `what`.
Eigen::MatrixXd matrixFrom(const json& rows, int n, const std::string& what);
/// {"matrix", "scale", "rotation", "translation", "rotation_angle_deg"}.
json transformJson(const SimilarityTransform& t);
SimilarityTransform transformFrom(const json& j, const std::string& what);
/// Every option, in the units the names say (mm, px, deg); infinite values as null.
json optionsJson(const RegistrationOptions& o);
/**
 * The int under `key`, or `fallback` when absent. A number outside int's
 * range or with a fraction is an error (converting it would be undefined
 * behaviour). @throws vimlop::Error naming the key.
 */
int intValue(const json& j, const char* key, int fallback);
/// `j[key]` into `field` when present: ints must be whole numbers, a null
/// double is +infinity (as optionsJson writes it). @throws vimlop::Error naming the key.
void readValue(const json& j, const char* key, double& field);
void readValue(const json& j, const char* key, int& field);
void readValue(const json& j, const char* key, bool& field);
/// Options from optionsJson() (every row of RegistrationOptionTable.h and
/// the method, Σ2d and scale bounds); keys not given keep their defaults.
RegistrationOptions optionsFrom(const json& j);
/// {"vimlop": VIMLOP's version, then each of `record.versions`}.
json versionsJson(const RegistrationRecord& record);
/// Each input as {"role", "path", "bytes", "sha256"}.
json inputsJson(const RegistrationRecord& record);

} // namespace vimlop::recordjson

#endif
