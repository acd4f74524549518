// The facesocial subcommands. Each takes the arguments after its name and returns an exit code.
#pragma once

#include <filesystem>
#include <string>
#include <vector>

namespace facesocial::cli {

int cmd_detect(const std::vector<std::string>& args);
int cmd_eval(const std::vector<std::string>& args);
int cmd_eval_orl(const std::vector<std::string>& args);
int cmd_eval_identify(const std::vector<std::string>& args);
int cmd_eval_unknown(const std::vector<std::string>& args);
int cmd_enrol(const std::vector<std::string>& args);
int cmd_train(const std::vector<std::string>& args);
int cmd_forget(const std::vector<std::string>& args);
int cmd_recognize(const std::vector<std::string>& args);
int cmd_watch(const std::vector<std::string>& args);
int cmd_tag(const std::vector<std::string>& args);
int cmd_eval_tagging(const std::vector<std::string>& args);
int cmd_eval_training_policy(const std::vector<std::string>& args);
int cmd_eval_window(const std::vector<std::string>& args);
int cmd_eval_threshold(const std::vector<std::string>& args);
int cmd_eval_throughput(const std::vector<std::string>& args);

/// The image files named by a command line: a file as is, a folder as its images.
std::vector<std::filesystem::path> expand_inputs(const std::vector<std::string>& inputs);

/// --data DIR if given, else $FACESOCIAL_DATA.
std::filesystem::path data_dir(const std::string& option_value);

}  // namespace facesocial::cli
