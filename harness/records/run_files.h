// A run's own files: series.csv.gz (the sampled trajectory, gzipped) and events.csv (one row per contact
// episode), written and read back (reports and errors against a saved reference read them). Units are
// named in every column.
#pragma once

#include <array>
#include <istream>
#include <stdexcept>
#include <string>
#include <vector>

#include "model/trajectory.h"

namespace ib {

// A result file or folder that cannot be written (full disk, no permission, a path under a file). It
// stops a suite: every later run would be lost the same way. what() names the file, the OS's reason and
// what to do; the command exits with its own code (cli/main.cpp).
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};
// The message of an OutputError: "<path>: cannot <action>: <reason>; <what to do>". `error` is an errno.
std::string output_error_text(const std::string& path, const std::string& action, int error);

// Small result files written whole, appended to, or replaced through a temporary and a rename (so that a
// failed write leaves the old file as it was); each checked after writing, flushing and closing.
// Throw OutputError.
void write_text_file(const std::string& path, const std::string& text);
// Empties a run's folder of its own files (a previous, unfinished attempt's), creating it when absent. Its
// subfolders stay: they are other runs' (a job's ensemble starts and its chain reference are below its id).
// Throws OutputError when the folder cannot be made.
void clear_run_folder(const std::string& folder);
// The whole of a file as it is; "" when it is absent or cannot be read (callers that must tell the two
// apart check first). The one whole-file reader of the harness.
std::string read_text_file(const std::string& path);
void append_text_file(const std::string& path, const std::string& text);
void replace_text_file(const std::string& path, const std::string& text);

// Write errors throw OutputError; read errors std::runtime_error, both naming the file. A path ending in
// .gz is written gzipped; the readers take either form (a plain series.csv from another solver, `score`).
void write_series_csv(const std::string& path, const Trajectory& trajectory);
void write_events_csv(const std::string& path, const Trajectory& trajectory);
// The series as a file keeps it at a lower rate: every k-th sample from the first, k the whole number of output
// samples per kept one (the largest rate at most rate_hz that divides the output rate); each peak column the
// largest peak of the k intervals its sample now closes, so that no peak is lost. The events, the energy
// baseline and the rest are kept. rate_hz <= 0 or at least the output rate: the series as it is.
Trajectory series_at_rate(const Trajectory& trajectory, double rate_hz);
// sensor.csv.gz: the accelerometer's reading of both frames at its own rate (metrics.h
// sensor_acceleration, the one computation of it): time_s (window centres, exact),
// frame{1,2}_sensor_acceleration_m_s2. The report draws it instead of computing it again.
void write_sensor_csv(const std::string& path, const std::vector<double>& time_s,
                      const std::array<std::vector<double>, 2>& acceleration_m_s2);
// Fills the series (and output rate, start time) or the events of `trajectory` from a file written above.
void read_series_csv(const std::string& path, Trajectory& trajectory);
void read_events_csv(const std::string& path, Trajectory& trajectory);
// The series file of a run folder: series.csv.gz when it is there, else series.csv.
std::string series_file(const std::string& run_folder);
// The same from a stream; `name` is the file named in messages (the fuzz targets read from memory).
void read_series_csv(std::istream& in, const std::string& name, Trajectory& trajectory);
void read_events_csv(std::istream& in, const std::string& name, Trajectory& trajectory);

}  // namespace ib
