#include "run_files.h"

#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <limits>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <vector>

namespace ib {
namespace {

struct FileCloser {
  void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

File open_for_writing(const std::string& path) {
  File f(std::fopen(path.c_str(), "w"));
  if (!f) throw OutputError(output_error_text(path, "create", errno));
  return f;
}

// Flushes and closes: a full disk shows at the flush or the close, never silently.
void finish(File& f, const std::string& path) {
  errno = 0;
  const bool flushed = std::fflush(f.get()) == 0 && !std::ferror(f.get());
  int error = errno;
  const bool closed = std::fclose(f.release()) == 0;
  if (!closed && error == 0) error = errno;
  if (!flushed || !closed) throw OutputError(output_error_text(path, "write", error));
}

constexpr const char* kSeriesHeader =
    "time_s,frame1_displacement_m,frame1_velocity_m_s,frame1_acceleration_m_s2,"
    "frame2_displacement_m,frame2_velocity_m_s,frame2_acceleration_m_s2,contact_force_n,"
    "frame1_peak_abs_acceleration_m_s2,frame2_peak_abs_acceleration_m_s2,peak_contact_force_n,mechanical_energy_j";
constexpr const char* kEventsHeader =
    "onset_time_s,end_time_s,duration_s,approach_velocity_m_s,rebound_velocity_m_s,restitution,"
    "peak_force_n,impulse_n_s,max_indentation_m";

// Rows of numbers after a known header; an empty cell is NaN.
std::vector<std::vector<double>> read_table(std::istream& in, const std::string& path, const std::string& header,
                                            std::size_t columns) {
  std::string line;
  if (!std::getline(in, line) || line != header)
    throw std::runtime_error(path + ":1: unexpected header; expected: " + header);
  std::vector<std::vector<double>> rows;
  int number = 1;
  while (std::getline(in, line)) {
    ++number;
    if (line.empty()) continue;
    std::vector<double> row;
    std::stringstream cells(line);
    for (std::string cell; std::getline(cells, cell, ',');) {
      char* end = nullptr;
      const double v = cell.empty() ? std::numeric_limits<double>::quiet_NaN() : std::strtod(cell.c_str(), &end);
      if (!cell.empty() && *end != '\0')
        throw std::runtime_error(path + ":" + std::to_string(number) + ": not a number: '" + cell + "'");
      row.push_back(v);
    }
    if (!line.empty() && line.back() == ',') row.push_back(std::numeric_limits<double>::quiet_NaN());
    if (row.size() != columns)
      throw std::runtime_error(path + ":" + std::to_string(number) + ": " + std::to_string(row.size()) +
                               " values; expected " + std::to_string(columns));
    rows.push_back(std::move(row));
  }
  if (in.bad()) throw std::runtime_error(path + ": read error");
  return rows;
}

std::ifstream open_for_reading(const std::string& path) {
  errno = 0;
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read: " + std::strerror(errno ? errno : ENOENT));
  return in;
}

void print(std::FILE* f, double value, const char* format) {
  if (std::isfinite(value)) std::fprintf(f, format, value);
}

}  // namespace

std::string output_error_text(const std::string& path, const std::string& action, int error) {
  std::string advice;
  switch (error) {
    case ENOSPC:
    case EDQUOT:
      advice = "free space on that disk (or choose another output folder), then continue the suite with --resume";
      break;
    case EACCES:
    case EPERM:
    case EROFS:
      advice = "make the folder writable (or choose another output folder)";
      break;
    case ENOTDIR:
      advice = "a part of the path is a file, not a folder: choose another output folder";
      break;
    default:
      advice = "check the output folder (or choose another one)";
  }
  return path + ": cannot " + action + ": " + (error ? std::strerror(error) : "unknown error") + "; " + advice;
}

namespace {

// Writes `text` to a file opened with `mode`; the errno of what failed, 0 when all went well.
int put_text(const std::string& path, const char* mode, const std::string& text) {
  std::FILE* f = std::fopen(path.c_str(), mode);
  if (!f) return errno ? errno : EIO;
  errno = 0;
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size() && std::fflush(f) == 0;
  int error = written ? 0 : (errno ? errno : EIO);
  if (std::fclose(f) != 0 && error == 0) error = errno ? errno : EIO;
  return error;
}

}  // namespace

void write_text_file(const std::string& path, const std::string& text) {
  if (const int error = put_text(path, "w", text)) throw OutputError(output_error_text(path, "write", error));
}

void append_text_file(const std::string& path, const std::string& text) {
  if (const int error = put_text(path, "a", text)) throw OutputError(output_error_text(path, "append to", error));
}

void replace_text_file(const std::string& path, const std::string& text) {
  const std::string temporary = path + ".tmp";
  int error = put_text(temporary, "w", text);
  if (!error && std::rename(temporary.c_str(), path.c_str()) != 0) error = errno;
  if (error) {
    std::remove(temporary.c_str());
    throw OutputError(output_error_text(path, "rewrite", error));
  }
}

void write_series_csv(const std::string& path, const Trajectory& t) {
  File f = open_for_writing(path);
  std::fprintf(f.get(), "%s\n", kSeriesHeader);
  const bool energy = t.mechanical_energy_j.size() == t.size();
  for (std::size_t k = 0; k < t.size(); ++k) {
    // 17 significant digits for time and displacement (errors against a saved reference read them back)
    const double values[] = {t.displacement_m[0][k], t.velocity_m_s[0][k], t.acceleration_m_s2[0][k],
                             t.displacement_m[1][k], t.velocity_m_s[1][k], t.acceleration_m_s2[1][k],
                             t.contact_force_n[k], t.peak_abs_acceleration_m_s2[0][k],
                             t.peak_abs_acceleration_m_s2[1][k], t.peak_contact_force_n[k]};
    print(f.get(), t.time_s[k], "%.17g");
    for (double v : values) {
      std::fputc(',', f.get());
      print(f.get(), v, "%.17g");
    }
    std::fputc(',', f.get());
    if (energy) print(f.get(), t.mechanical_energy_j[k], "%.17g");
    std::fputc('\n', f.get());
  }
  finish(f, path);
}

void write_events_csv(const std::string& path, const Trajectory& t) {
  File f = open_for_writing(path);
  std::fprintf(f.get(), "%s\n", kEventsHeader);
  for (const ContactEvent& e : t.events) {
    const double values[] = {e.onset_time_s,        e.end_time_s,  e.end_time_s - e.onset_time_s,
                             e.approach_velocity_m_s, e.rebound_velocity_m_s, e.restitution,
                             e.peak_force_n,          e.impulse_n_s, e.max_indentation_m};
    for (std::size_t i = 0; i < std::size(values); ++i) {
      if (i) std::fputc(',', f.get());
      print(f.get(), values[i], "%.17g");
    }
    std::fputc('\n', f.get());
  }
  finish(f, path);
}

void read_series_csv(const std::string& path, Trajectory& t) {
  std::ifstream in = open_for_reading(path);
  read_series_csv(in, path, t);
}

void read_events_csv(const std::string& path, Trajectory& t) {
  std::ifstream in = open_for_reading(path);
  read_events_csv(in, path, t);
}

void read_series_csv(std::istream& in, const std::string& path, Trajectory& t) {
  const auto rows = read_table(in, path, kSeriesHeader, 12);
  t = Trajectory{};
  t.reserve(rows.size());
  for (const auto& r : rows) {
    t.time_s.push_back(r[0]);
    for (int f = 0; f < 2; ++f) {
      t.displacement_m[f].push_back(r[1 + 3 * f]);
      t.velocity_m_s[f].push_back(r[2 + 3 * f]);
      t.acceleration_m_s2[f].push_back(r[3 + 3 * f]);
      t.peak_abs_acceleration_m_s2[f].push_back(r[8 + f]);
    }
    t.contact_force_n.push_back(r[7]);
    t.peak_contact_force_n.push_back(r[10]);
    if (std::isfinite(r[11])) t.mechanical_energy_j.push_back(r[11]);
  }
  if (t.mechanical_energy_j.size() != t.size()) t.mechanical_energy_j.clear();
  if (t.size() >= 2) {
    t.start_time_s = t.time_s.front();
    t.output_rate_hz = static_cast<double>(t.size() - 1) / (t.time_s.back() - t.time_s.front());
  }
}

void read_events_csv(std::istream& in, const std::string& path, Trajectory& t) {
  t.events.clear();
  for (const auto& r : read_table(in, path, kEventsHeader, 9)) {
    ContactEvent e;
    e.onset_time_s = r[0];
    e.end_time_s = r[1];
    e.approach_velocity_m_s = r[3];
    e.rebound_velocity_m_s = r[4];
    e.restitution = r[5];
    e.peak_force_n = r[6];
    e.impulse_n_s = r[7];
    e.max_indentation_m = r[8];
    t.events.push_back(e);
  }
}

}  // namespace ib
