#pragma once
//! \file csv_writer.h
//! The experiments' CSV files and their metadata (header only: each experiments/*.cpp is one
//! program).
//!
//! Convention: NAME.csv has one line of column names, then one row per run; numbers are written
//! in the shortest form that reads back to the same double (`0.06`, not `0.059999999999999998`);
//! fields never contain commas.  Beside it, NAME.csv.json holds the metadata:
//! `{"program": NAME, "git": REV, "date": ISO8601, "parameters": {KEY: "VALUE", ...}}`
//! (every parameter value a string, as the program formatted it).

#include <charconv>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

namespace delmesh::experiments {

//! `git rev-parse --short HEAD` of the source tree this program was built from (plus "-dirty" if
//! tracked files differ), or "unknown" if that tree is gone or not a repository.
inline std::string git_revision() {
  const std::string source_dir = std::filesystem::path(__FILE__).parent_path().string();
  auto run = [](const std::string& command) {
    std::string text;
    if (FILE* pipe = ::popen(command.c_str(), "r")) {
      char buffer[256];
      while (std::fgets(buffer, sizeof buffer, pipe)) text += buffer;
      ::pclose(pipe);
    }
    while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
    return text;
  };
  const std::string git = "git -C '" + source_dir + "' ";
  std::string revision = run(git + "rev-parse --short HEAD 2>/dev/null");
  if (revision.empty()) return "unknown";
  if (!run(git + "status --porcelain --untracked-files=no 2>/dev/null").empty()) revision += "-dirty";
  return revision;
}

inline std::string utc_now() {
  const std::time_t now = std::time(nullptr);
  char text[32];
  std::strftime(text, sizeof text, "%Y-%m-%dT%H:%M:%SZ", std::gmtime(&now));
  return text;
}

//! The path of the metadata file of the CSV file `csv`: the same name with ".json" appended.
inline std::filesystem::path metadata_path(const std::filesystem::path& csv) {
  return std::filesystem::path(csv.string() + ".json");
}

//! The metadata of the CSV file `csv` (its NAME.csv.json).  Throws std::runtime_error if that file
//! cannot be read or is not a JSON object.
inline nlohmann::json read_metadata(const std::filesystem::path& csv) {
  std::ifstream in(metadata_path(csv));
  if (!in) throw std::runtime_error("cannot read " + metadata_path(csv).string());
  nlohmann::json meta = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!meta.is_object()) throw std::runtime_error(metadata_path(csv).string() + " is not a JSON object");
  return meta;
}

//! A CSV file: the column names, then rows; and its metadata file.  Both are written under
//! temporary names and renamed by close() (or the destructor), so a crashed run never leaves a
//! half file under the final names.
class CsvWriter {
 public:
  //! Opens `path` (creating its directory) and writes the column line, and the metadata with the
  //! program name, the git revision, the date and `parameters` in that order.  Throws
  //! std::runtime_error if either file cannot be written.
  CsvWriter(const std::filesystem::path& path, const std::string& program,
            const std::vector<std::pair<std::string, std::string>>& parameters,
            const std::vector<std::string>& columns)
      : path_(path), temporary_(path.string() + ".partial"),
        meta_temporary_(metadata_path(path).string() + ".partial"), columns_(columns.size()) {
    if (path.has_parent_path()) std::filesystem::create_directories(path.parent_path());
    nlohmann::ordered_json meta{{"program", program}, {"git", git_revision()}, {"date", utc_now()}};
    meta["parameters"] = nlohmann::ordered_json::object();
    for (const auto& [key, value] : parameters) meta["parameters"][key] = value;
    {
      std::ofstream meta_out(meta_temporary_);
      meta_out << meta.dump(2) << '\n';
      if (!meta_out) throw std::runtime_error("cannot write " + meta_temporary_.string());
    }
    out_.open(temporary_);
    if (!out_) throw std::runtime_error("cannot write " + temporary_.string());
    for (std::size_t i = 0; i < columns.size(); ++i) out_ << (i ? "," : "") << columns[i];
    out_ << '\n';
  }
  ~CsvWriter() { close(); }
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  //! One row; the number of fields must equal the number of columns (else std::logic_error).
  void row(const std::vector<std::string>& fields) {
    if (fields.size() != columns_) throw std::logic_error("CSV row has the wrong number of fields");
    for (std::size_t i = 0; i < fields.size(); ++i) out_ << (i ? "," : "") << fields[i];
    out_ << '\n';
    out_.flush();
  }
  //! Closes the file and gives both files their final names (no effect if already closed).
  void close() {
    if (!out_.is_open()) return;
    out_.close();
    std::filesystem::rename(meta_temporary_, metadata_path(path_));
    std::filesystem::rename(temporary_, path_);
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_, temporary_, meta_temporary_;
  std::size_t columns_;
  std::ofstream out_;
};

//! A double as the shortest decimal text that reads back to the same value (std::to_chars);
//! "nan", "inf", "-inf" for the non-finite values.
inline std::string field(double value) {
  if (!std::isfinite(value)) return std::isnan(value) ? "nan" : (value > 0 ? "inf" : "-inf");
  char text[64];
  const auto result = std::to_chars(text, text + sizeof text, value);
  return std::string(text, result.ptr);
}
inline std::string field(long long value) { return std::to_string(value); }
inline std::string field(std::size_t value) { return std::to_string(value); }
inline std::string field(int value) { return std::to_string(value); }
inline std::string field(bool value) { return value ? "1" : "0"; }
inline std::string field(const std::string& value) { return value; }
inline std::string field(const char* value) { return value; }
//! A list of integers as "a;b;c" (semicolons keep the CSV comma-separated).
inline std::string field(const std::vector<int>& values) {
  std::string text;
  for (std::size_t i = 0; i < values.size(); ++i) text += (i ? ";" : "") + std::to_string(values[i]);
  return text;
}

}  // namespace delmesh::experiments
