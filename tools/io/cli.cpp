// The command-line parser of cli.hpp: CLI11, compiled here once for every ntn tool.

#include "cli.hpp"

#include <CLI/CLI.hpp>
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <cstring>

namespace ntn::cli {

struct App::Parts {
  std::unique_ptr<CLI::App> top;
  std::vector<std::unique_ptr<Option>> options;
  std::vector<std::unique_ptr<App>> subcommands;
};

Validator IsMember(std::vector<std::string> values) {
  // as a Validator: a copy of an IsMember would take IsMember's template constructor
  const CLI::Validator member = CLI::IsMember(std::move(values));
  return Validator([member](std::string& text) { return member(text); }, member.get_description());
}

Option* Option::check(const Validator& v) {
  o_->check(CLI::Validator([v](std::string& text) { return v(text); }, v.description()));
  return this;
}

Option* Option::required() {
  o_->required();
  return this;
}

Option* Option::capture_default_str() {
  o_->capture_default_str();
  return this;
}

Option* Option::needs(const std::string& name) {
  o_->needs(name);
  return this;
}

Option* Option::excludes(Option* other) {
  o_->excludes(other->o_);
  return this;
}

Option* Option::delimiter(char c) {
  o_->delimiter(c);
  return this;
}

std::size_t Option::count() const {
  return o_->count();
}

namespace {

// At exit: what the program wrote to standard output must have reached it. A write error (a full
// disk, /dev/full, a closed pipe's EPIPE with SIGPIPE ignored, a closed descriptor) is the
// program's error, whatever its own exit code was: exit 2 with a message, as a write error on
// any file the program names.
void check_standard_output() {
  errno = 0;
  if (std::fflush(stdout) == 0 && std::ferror(stdout) == 0) return;
  const int e = errno != 0 ? errno : EIO;
  std::fprintf(stderr, "error: write error on standard output: %s\n", std::strerror(e));
  std::_Exit(2);
}

}  // namespace

// Every tool makes one App to parse its command line: its construction registers the check of
// standard output at exit, once per program.
App::App(std::string description, std::string name) : owned_(std::make_unique<Parts>()) {
  static const bool registered = std::atexit(check_standard_output) == 0;
  (void)registered;
  owned_->top = std::make_unique<CLI::App>(std::move(description), std::move(name));
  app_ = owned_->top.get();
  parts_ = owned_.get();
}

App::App(CLI::App* app, Parts* parts) : app_(app), parts_(parts) {}

App::~App() = default;

#define NTN_CLI_ADD_OPTION(T)                                                           \
  Option* App::add_option(std::string name, T& value, std::string description) {        \
    parts_->options.push_back(std::unique_ptr<Option>(                                  \
        new Option(app_->add_option(std::move(name), value, std::move(description))))); \
    return parts_->options.back().get();                                                \
  }
NTN_CLI_ADD_OPTION(std::string)
NTN_CLI_ADD_OPTION(std::vector<std::string>)
NTN_CLI_ADD_OPTION(std::vector<double>)
NTN_CLI_ADD_OPTION(double)
NTN_CLI_ADD_OPTION(int)
NTN_CLI_ADD_OPTION(long)
NTN_CLI_ADD_OPTION(unsigned)
NTN_CLI_ADD_OPTION(unsigned long)
#undef NTN_CLI_ADD_OPTION

Option* App::add_flag(std::string name, bool& value, std::string description) {
  parts_->options.push_back(std::unique_ptr<Option>(
      new Option(app_->add_flag(std::move(name), value, std::move(description)))));
  return parts_->options.back().get();
}

App* App::add_subcommand(std::string name, std::string description) {
  CLI::App* sub = app_->add_subcommand(std::move(name), std::move(description));
  parts_->subcommands.push_back(std::unique_ptr<App>(new App(sub, parts_)));
  return parts_->subcommands.back().get();
}

App* App::require_subcommand(int count) {
  app_->require_subcommand(count);
  return this;
}

void App::silence_failures() {
  app_->failure_message([](const CLI::App*, const CLI::Error&) { return std::string(); });
}

bool App::parsed() const {
  return app_->parsed();
}

std::size_t App::count(const std::string& name) const {
  return app_->count(name);
}

std::optional<int> App::parse(int argc, const char* const* argv) {
  try {
    app_->parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app_->exit(e);
    return code == 0 ? 0 : 2;
  }
  return std::nullopt;
}

}  // namespace ntn::cli
