// A process's main body with the project's exit codes: 0 done, 1 failed at run time, 2 bad
// configuration (config file, QoS profiles, command line), each with a message naming the cause.
#pragma once

#include <functional>

namespace uavslam::process {

int run_node(const char* name, const std::function<int()>& body);

}  // namespace uavslam::process
