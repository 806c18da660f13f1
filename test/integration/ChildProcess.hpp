// The tests start real processes with the launcher's ChildProcess (components/common).
#pragma once

#include "../../components/common/ChildProcess.hpp"

namespace uavslam::test {
using process::ChildProcess;
}  // namespace uavslam::test
