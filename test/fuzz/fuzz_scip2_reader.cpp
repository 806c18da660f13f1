// libFuzzer target: the SCIP 2.0 response framer, scan decoding, the PP/VV parsing and the
// session (src/drivers/scip2). Any byte stream, split anywhere, must give counted garbage and
// damaged replies, never a crash, undefined behaviour, or a read past the input.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <vector>

#include "drivers/scip2/ResponseReader.hpp"
#include "drivers/scip2/ScanReply.hpp"
#include "drivers/scip2/SensorDescription.hpp"
#include "drivers/scip2/Session.hpp"

namespace {

using namespace uavslam::drivers::scip2;

void decode_everything(const std::vector<Response>& responses) {
  for (const Response& r : responses) {
    std::string problem;
    if (const auto request = parse_scan_echo(r.echo)) decode_scan(r, *request, problem);
    const InfoFields fields = parse_info_lines(r.data);
    if (const auto sensor = describe_sensor(fields, fields, problem)) {
      sensor->angle_of_step(sensor->last_step);
    }
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view bytes(reinterpret_cast<const char*>(data), size);
  // The first byte chooses the chunk size, as reads split a stream.
  const std::size_t chunk = size > 0 ? 1 + data[0] % 97 : 1;
  ResponseReader reader;
  std::vector<Response> responses;
  for (std::size_t at = 0; at < bytes.size(); at += chunk) {
    reader.feed(bytes.substr(at, chunk), responses);
  }
  decode_everything(responses);

  Session session;
  session.start(0.0);
  double now = 0.0;
  for (std::size_t at = 0; at < bytes.size(); at += chunk) {
    now += 0.01;
    session.receive(bytes.substr(at, chunk), now);
    session.tick(now);
    session.take_output();
    session.take_scans();
    if (session.state() == Session::State::Failed) session.start(now);
  }
  return 0;
}
