#include "cli/journal.hpp"

#include <stdexcept>

namespace collide2d::cli {

void read_journal(const std::string& path, const nlohmann::json& options, const std::function<void(const nlohmann::json&)>& take) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot open file (nothing to resume)");
  std::string text;
  int line = 0;
  try {
    while (std::getline(in, text)) {
      ++line;
      const nlohmann::json j = nlohmann::json::parse(text);
      if (line == 1) {
        if (!j.contains("options") || j["options"] != options)
          throw std::runtime_error("written with other options (" + j.value("options", nlohmann::json()).dump() +
                                   "); run it with those, or remove the file");
        continue;
      }
      take(j);
    }
  } catch (const nlohmann::json::exception& e) {
    if (in.eof() && line > 1) return;  // the last line, cut short by a kill
    throw std::runtime_error(path + ": line " + std::to_string(line) + ": " + e.what());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path + ": line " + std::to_string(line) + ": " + e.what());
  }
  if (line == 0) throw std::runtime_error(path + ": empty (no options line)");
}

JournalWriter::JournalWriter(const std::string& path, const nlohmann::json& options, bool append) : path_(path) {
  out_.open(path, append ? std::ios::app : std::ios::trunc);
  if (!out_) throw std::runtime_error(path + ": cannot write the journal of finished work");
  if (!append) write({{"options", options}});
}

void JournalWriter::write(const nlohmann::json& line) {
  out_ << line.dump() << "\n";
  out_.flush();
  if (!out_) throw std::runtime_error(path_ + ": error writing the journal of finished work");
}

}  // namespace collide2d::cli
