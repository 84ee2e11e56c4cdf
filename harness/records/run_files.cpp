#include "harness/records/run_files.h"

#include <libdeflate.h>
#include <zlib.h>
#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <memory>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <vector>

#include "harness/records/number_text.h"

namespace ib {
namespace {

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
// opened (when given) says whether the file could be opened at all.
int put_text(const std::string& path, const char* mode, std::string_view text, bool* opened = nullptr) {
  std::FILE* f = std::fopen(path.c_str(), mode);
  if (opened) *opened = f != nullptr;
  if (!f) return errno ? errno : EIO;
  errno = 0;
  const bool written = std::fwrite(text.data(), 1, text.size(), f) == text.size() && std::fflush(f) == 0;
  int error = written ? 0 : (errno ? errno : EIO);
  if (std::fclose(f) != 0 && error == 0) error = errno ? errno : EIO;
  return error;
}

}  // namespace

std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

void clear_run_folder(const std::string& folder) {
  std::error_code error;
  for (const std::filesystem::directory_entry& entry : std::filesystem::directory_iterator(folder, error))
    if (!entry.is_directory(error)) std::filesystem::remove(entry.path(), error);
  std::filesystem::create_directories(folder, error);
  if (error) throw OutputError(output_error_text(folder, "create the run folder", error.value()));
}

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

namespace {

bool gzipped(const std::string& path) { return path.size() > 3 && path.compare(path.size() - 3, 3, ".gz") == 0; }

// A table's text in the gzip format (which zcat, zlib and pandas read), compressed whole in memory by
// libdeflate at its fastest level: a study writes hundreds of these files, and libdeflate's level 1 takes
// less CPU than zlib's level 1 for a smaller file, while its higher levels cost twice that and more for
// files a few percent smaller (docs/performance.md, "Compressing the result tables"). The text is already
// whole in memory, so a streaming compressor would save nothing. The bytes are returned in `buffer`,
// libdeflate's worst-case bound left uninitialised: zero-filling it would touch about twice the memory the
// output needs, each page a fault, for nothing.
std::string_view gzip_text(const std::string& text, std::unique_ptr<char[]>& buffer) {
  const std::unique_ptr<libdeflate_compressor, void (*)(libdeflate_compressor*)> compressor(
      libdeflate_alloc_compressor(1), libdeflate_free_compressor);
  if (!compressor) throw std::bad_alloc();
  const std::size_t bound = libdeflate_gzip_compress_bound(compressor.get(), text.size());
  buffer.reset(new char[bound]);
  const std::size_t size = libdeflate_gzip_compress(compressor.get(), text.data(), text.size(), buffer.get(), bound);
  // The bound is libdeflate's own worst case: a result of 0 (no room) would be a bug, not bad input.
  if (size == 0) throw std::logic_error("libdeflate_gzip_compress: the output did not fit its bound");
  return {buffer.get(), size};
}

// A table's text, written whole: gzipped when the path ends in .gz, plain otherwise. Checked after
// writing and closing, like every result file.
void write_table(const std::string& path, const std::string& text) {
  std::unique_ptr<char[]> compressed;
  const bool compress = gzipped(path);
  bool opened = false;
  if (const int error = put_text(path, compress ? "wb" : "w", compress ? gzip_text(text, compressed) : text, &opened))
    throw OutputError(output_error_text(path, opened ? "write" : "create", error));
}

// A table's text, gzipped or plain (zlib reads a plain file as it is).
std::string read_table_text(const std::string& path) {
  errno = 0;
  gzFile f = gzopen(path.c_str(), "rb");
  if (!f) throw std::runtime_error(path + ": cannot read: " + std::strerror(errno ? errno : ENOENT));
  std::string text;
  char buffer[1 << 16];
  int n = 0;
  while ((n = gzread(f, buffer, sizeof buffer)) > 0) text.append(buffer, static_cast<std::size_t>(n));
  // A file cut short (a run stopped while writing it, a full disk) ends without error from gzread: zlib says so
  // only through gzerror's Z_BUF_ERROR, and a resumed study must not take such a file for a whole one.
  int code = Z_OK;
  const std::string reason = gzerror(f, &code);
  gzclose(f);
  if (n < 0 || code == Z_BUF_ERROR)
    throw std::runtime_error(path + ": cannot read: " + (reason.empty() ? "not a valid gzip file" : reason));
  return text;
}

void add_cell(std::string& line, const std::string& cell, bool first) {
  if (!first) line += ',';
  line += cell;
}

}  // namespace

std::string series_file(const std::string& run_folder) {
  const std::string plain = run_folder + "/series.csv";
  std::error_code error;
  return std::filesystem::exists(plain + ".gz", error) ? plain + ".gz" : plain;
}

void write_series_csv(const std::string& path, const Trajectory& t) {
  std::string text = std::string(kSeriesHeader) + "\n";
  text.reserve(t.size() * 130);
  const bool energy = t.mechanical_energy_j.size() == t.size();
  for (std::size_t k = 0; k < t.size(); ++k) {
    const double values[] = {t.displacement_m[0][k],
                             t.velocity_m_s[0][k],
                             t.acceleration_m_s2[0][k],
                             t.displacement_m[1][k],
                             t.velocity_m_s[1][k],
                             t.acceleration_m_s2[1][k],
                             t.contact_force_n[k],
                             t.peak_abs_acceleration_m_s2[0][k],
                             t.peak_abs_acceleration_m_s2[1][k],
                             t.peak_contact_force_n[k]};
    // The time exactly, so that a series read back lies on its sample grid (the sensor reading takes
    // samples as exact, metrics.cpp); the values with 9 digits.
    text += exact_number_text(t.time_s[k]);
    for (double v : values) add_cell(text, number_text(v), false);
    add_cell(text, energy ? number_text(t.mechanical_energy_j[k]) : "", false);
    text += '\n';
  }
  write_table(path, text);
}

Trajectory series_at_rate(const Trajectory& t, double rate_hz) {
  const std::size_t k = rate_hz > 0 && t.output_rate_hz > rate_hz
                            ? static_cast<std::size_t>(std::floor(t.output_rate_hz / rate_hz * (1 + 1e-12)))
                            : 1;
  if (k <= 1 || t.size() == 0) return t;
  Trajectory kept;
  kept.output_rate_hz = t.output_rate_hz / static_cast<double>(k);
  kept.start_time_s = t.start_time_s;
  kept.initial_mechanical_energy_j = t.initial_mechanical_energy_j;
  kept.events = t.events;
  const bool energy = t.mechanical_energy_j.size() == t.size();
  kept.reserve(t.size() / k + 1);
  for (std::size_t j = 0; j < t.size(); j += k) {
    kept.time_s.push_back(t.time_s[j]);
    kept.contact_force_n.push_back(t.contact_force_n[j]);
    if (energy) kept.mechanical_energy_j.push_back(t.mechanical_energy_j[j]);
    double peak_force = t.peak_contact_force_n[j];
    for (int f = 0; f < 2; ++f) {
      kept.displacement_m[f].push_back(t.displacement_m[f][j]);
      kept.velocity_m_s[f].push_back(t.velocity_m_s[f][j]);
      kept.acceleration_m_s2[f].push_back(t.acceleration_m_s2[f][j]);
      double peak = t.peak_abs_acceleration_m_s2[f][j];
      for (std::size_t i = j >= k ? j - k + 1 : j; i < j; ++i)
        peak = std::max(peak, t.peak_abs_acceleration_m_s2[f][i]);
      kept.peak_abs_acceleration_m_s2[f].push_back(peak);
    }
    for (std::size_t i = j >= k ? j - k + 1 : j; i < j; ++i)
      peak_force = std::max(peak_force, t.peak_contact_force_n[i]);
    kept.peak_contact_force_n.push_back(peak_force);
  }
  return kept;
}

void write_sensor_csv(const std::string& path, const std::vector<double>& time_s,
                      const std::array<std::vector<double>, 2>& acceleration_m_s2) {
  std::string text = "time_s,frame1_sensor_acceleration_m_s2,frame2_sensor_acceleration_m_s2\n";
  for (std::size_t k = 0; k < time_s.size(); ++k) {
    text += exact_number_text(time_s[k]);
    for (int f = 0; f < 2; ++f) add_cell(text, number_text(acceleration_m_s2[f][k]), false);
    text += '\n';
  }
  write_table(path, text);
}

void write_events_csv(const std::string& path, const Trajectory& t) {
  std::string text = std::string(kEventsHeader) + "\n";
  for (const ContactEvent& e : t.events) {
    // Onsets and ends exactly (they decide which impacts lie in a window); the rest with 9 digits.
    text += exact_number_text(e.onset_time_s);
    add_cell(text, exact_number_text(e.end_time_s), false);
    const double values[] = {e.end_time_s - e.onset_time_s,
                             e.approach_velocity_m_s,
                             e.rebound_velocity_m_s,
                             e.restitution,
                             e.peak_force_n,
                             e.impulse_n_s,
                             e.max_indentation_m};
    for (double v : values) add_cell(text, number_text(v), false);
    text += '\n';
  }
  write_table(path, text);
}

void read_series_csv(const std::string& path, Trajectory& t) {
  std::istringstream in(read_table_text(path));
  read_series_csv(in, path, t);
}

void read_events_csv(const std::string& path, Trajectory& t) {
  std::istringstream in(read_table_text(path));
  read_events_csv(in, path, t);
}

void read_series_csv(std::istream& in, const std::string& path, Trajectory& t) {
  const auto rows = read_table(in, path, kSeriesHeader, 12);
  // The metrics assume a series sampled at one rate (the sensor's windows, the peaks between samples):
  // times finite, increasing, evenly spaced (within 1e-6 of the spacing, what 17-digit times keep).
  // Line numbers count the header as line 1.
  if (rows.size() < 2)
    throw std::runtime_error(path + ": " + std::to_string(rows.size()) + " samples; allowed: at least 2");
  for (std::size_t i = 0; i < rows.size(); ++i) {  // first the order, then the spacing: the plainer fault first
    const double time = rows[i][0];
    const std::string where = path + ":" + std::to_string(i + 2) + ": time_s = ";
    if (!std::isfinite(time))
      throw std::runtime_error(where + "'" + std::to_string(time) + "'; allowed: a finite time");
    if (i > 0 && !(time > rows[i - 1][0]))
      throw std::runtime_error(where + exact_number_text(time) + " after " + exact_number_text(rows[i - 1][0]) +
                               "; allowed: increasing times");
  }
  const double spacing = (rows.back()[0] - rows.front()[0]) / static_cast<double>(rows.size() - 1);
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const double time = rows[i][0];
    const std::string where = path + ":" + std::to_string(i + 2) + ": time_s = ";
    const double expected = rows.front()[0] + spacing * static_cast<double>(i);
    if (std::abs(time - expected) > 1e-6 * spacing + 1e-12 * std::abs(time))
      throw std::runtime_error(where + exact_number_text(time) + ", expected " + exact_number_text(expected) +
                               "; allowed: samples evenly spaced (one output rate, here " + number_text(1 / spacing) +
                               " Hz)");
  }
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
  int line = 1;
  for (const auto& r : read_table(in, path, kEventsHeader, 9)) {
    ++line;
    const std::string where = path + ":" + std::to_string(line) + ": ";
    if (!std::isfinite(r[0]) || !std::isfinite(r[1]))
      throw std::runtime_error(where + "onset or end time not a finite number; allowed: finite times");
    if (r[1] < r[0])
      throw std::runtime_error(where + "the contact ends (" + exact_number_text(r[1]) + " s) before it begins (" +
                               exact_number_text(r[0]) + " s); allowed: end_time_s >= onset_time_s");
    if (!t.events.empty() && r[0] < t.events.back().onset_time_s)
      throw std::runtime_error(where + "onset " + exact_number_text(r[0]) + " s before the previous one (" +
                               exact_number_text(t.events.back().onset_time_s) + " s); allowed: events in time order");
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
