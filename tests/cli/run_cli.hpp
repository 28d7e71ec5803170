#pragma once
// Runs the built `rigidity` executable (RIGIDITY_EXECUTABLE) in a scratch working
// directory and captures its stdout, stderr and exit status.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>

namespace rigidity::testing {

namespace fs = std::filesystem;

struct CliOutcome {
  int exit_status = -1;
  std::string out;
  std::string err;
};

inline std::string shell_quote(const std::string& text) {
  std::string out = "'";
  for (const char c : text) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

inline std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

/// EXPECT_TRUE(contains(text, "needle")) prints the text when it fails.
inline ::testing::AssertionResult contains(const std::string& text, const std::string& needle) {
  if (text.find(needle) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "'" << needle << "' not found in:\n" << text;
}

/// A fresh working directory per test, removed afterwards.
class CliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("rigidity_cli_test_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  /// `rigidity ARGS` (ARGS as the shell would split them), run inside dir().
  CliOutcome rigidity(const std::string& args) const {
    const fs::path err_file = dir_ / ".stderr";
    const std::string command = "cd " + shell_quote(dir_.string()) + " && " + shell_quote(RIGIDITY_EXECUTABLE) + " " +
                                args + " 2> " + shell_quote(err_file.string());
    CliOutcome outcome;
    std::FILE* pipe = ::popen(command.c_str(), "r");
    if (pipe == nullptr) return outcome;
    std::array<char, 4096> buffer{};
    for (std::size_t n; (n = std::fread(buffer.data(), 1, buffer.size(), pipe)) > 0;)
      outcome.out.append(buffer.data(), n);
    const int status = ::pclose(pipe);
    outcome.exit_status = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
    outcome.err = read_text(err_file);
    fs::remove(err_file);
    return outcome;
  }

  /// Writes `text` to dir()/name and returns the file's name.
  std::string write_file(const std::string& name, const std::string& text) const {
    std::ofstream(dir_ / name) << text;
    return name;
  }

  [[nodiscard]] const fs::path& dir() const { return dir_; }

 private:
  fs::path dir_;
};

/// True if gnuplot is on PATH.
inline bool gnuplot_installed() { return std::system("command -v gnuplot > /dev/null 2>&1") == 0; }

/// A non-empty PNG image.
inline ::testing::AssertionResult is_png(const fs::path& path) {
  const std::string bytes = read_text(path);
  if (bytes.size() > 100 && bytes.compare(0, 8, "\x89PNG\r\n\x1a\n") == 0) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << path << " is not a non-empty PNG (" << bytes.size() << " bytes)";
}

/// PATH set to `value` while in scope.
class ScopedPath {
 public:
  explicit ScopedPath(const std::string& value) {
    if (const char* old = std::getenv("PATH")) saved_ = old;
    ::setenv("PATH", value.c_str(), 1);
  }
  ~ScopedPath() {
    if (saved_) {
      ::setenv("PATH", saved_->c_str(), 1);
    } else {
      ::unsetenv("PATH");
    }
  }
  ScopedPath(const ScopedPath&) = delete;
  ScopedPath& operator=(const ScopedPath&) = delete;

 private:
  std::optional<std::string> saved_;
};

}  // namespace rigidity::testing
