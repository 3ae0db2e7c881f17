#pragma once
// Command-line argument helpers shared by the commands.
#include <initializer_list>
#include <string>
#include <vector>

#include "sinew/io/storage_file.hpp"

namespace sinew::cli {

// `text` as a finite number, or a sinew::Error naming the option and what it got.
double parseNumber(const std::string& option, const std::string& text);

// --lowpass HZ for `motion`: refused at or above the Nyquist frequency of its smallest time step (OpenSim's
// filter would quietly use 0.49 of the sampling rate instead). Negative: no filtering, nothing checked.
void checkLowpassOption(double cutoffHz, const StorageTable& motion, const std::string& motionPath);

// Walks a command's arguments. A command's loop tests its options with is() and hands everything else to
// takePositional(), which fills the positional slots in order and refuses unknown options and extra
// arguments; --help prints the usage and ends the walk.
class ArgumentReader {
public:
    ArgumentReader(const std::vector<std::string>& args, const char* usage) : args_(args), usage_(usage) {}
    bool next();  // advances; false at the end or after --help
    bool is(const char* option) const { return args_[i_] == option; }
    bool is(const char* option, const char* alias) const { return is(option) || is(alias); }
    const std::string& value();  // the option's value; throws when missing
    double number();  // the option's value as a finite number; throws naming the option otherwise
    void takePositional(std::initializer_list<std::string*> slots);
    bool helpShown() const { return helpShown_; }
    // For a missing required argument: prints the usage on stderr and returns the exit code 2.
    int failWithUsage() const;

private:
    const std::vector<std::string>& args_;
    const char* usage_;
    std::size_t i_ = 0;
    bool started_ = false;
    bool helpShown_ = false;
};

}  // namespace sinew::cli
