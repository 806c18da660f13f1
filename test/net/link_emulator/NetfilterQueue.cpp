#include "NetfilterQueue.hpp"

#include <arpa/inet.h>
#include <errno.h>
#include <linux/netfilter.h>
#include <sys/socket.h>

#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>
#include <vector>

extern "C" {
#include <libnetfilter_queue/libnetfilter_queue.h>
#include <libnfnetlink/libnfnetlink.h>
}

namespace uavslam::net {
namespace {

// Large enough that a burst at the link rate does not overflow the socket before we read it.
constexpr unsigned kSocketBufferBytes = 8u << 20;
// An IP packet's largest size, and one netlink message of such a packet with its attributes.
constexpr unsigned kMaxPacketBytes = 0xffff;
constexpr std::size_t kReceiveBufferBytes = 0x20000;

[[noreturn]] void fail(const std::string& what) {
  throw std::runtime_error(what + ": " + std::strerror(errno));
}

}  // namespace

NetfilterQueue::NetfilterQueue(std::uint16_t number, std::uint32_t max_length, bool copy_packets,
                               PacketHandler on_packet)
    : number_(number), on_packet_(std::move(on_packet)) {
  library_ = nfq_open();
  if (library_ == nullptr) fail("nfq_open (needs root and the nfnetlink_queue module)");
  queue_ = nfq_create_queue(library_, number, &NetfilterQueue::on_message, this);
  if (queue_ == nullptr) {
    nfq_close(library_);
    fail("cannot bind NFQUEUE " + std::to_string(number) +
         " (needs root, and no other program on that queue)");
  }
  // The payload goes back unchanged with the verdict: copied only when someone looks into it.
  const int copied = copy_packets ? nfq_set_mode(queue_, NFQNL_COPY_PACKET, kMaxPacketBytes)
                                  : nfq_set_mode(queue_, NFQNL_COPY_META, 0);
  if (copied < 0 || nfq_set_queue_maxlen(queue_, max_length) < 0 ||
      nfq_set_queue_flags(queue_, NFQA_CFG_F_GSO | NFQA_CFG_F_FAIL_OPEN, NFQA_CFG_F_GSO) < 0) {
    nfq_destroy_queue(queue_);
    nfq_close(library_);
    fail("cannot configure NFQUEUE " + std::to_string(number));
  }
  nfnl_rcvbufsiz(nfq_nfnlh(library_), kSocketBufferBytes);
  fd_ = nfq_fd(library_);
}

NetfilterQueue::~NetfilterQueue() {
  nfq_destroy_queue(queue_);
  nfq_close(library_);
}

int NetfilterQueue::on_message(nfq_q_handle*, nfgenmsg*, nfq_data* packet, void* self) {
  const nfqnl_msg_packet_hdr* header = nfq_get_msg_packet_hdr(packet);
  if (header == nullptr) return 0;
  auto* queue = static_cast<NetfilterQueue*>(self);
  const std::uint32_t id = ntohl(header->packet_id);
  unsigned char* payload = nullptr;
  const int length = nfq_get_payload(packet, &payload);
  const bool kept = length > 0 ? queue->on_packet_(id, payload, static_cast<std::size_t>(length))
                               : queue->on_packet_(id, nullptr, 0);
  if (!kept) queue->drop(id);
  return 0;
}

void NetfilterQueue::receive() {
  std::vector<char> buffer(kReceiveBufferBytes);
  for (;;) {
    const ssize_t length = recv(fd_, buffer.data(), buffer.size(), MSG_DONTWAIT);
    if (length >= 0) {
      nfq_handle_packet(library_, buffer.data(), static_cast<int>(length));
      continue;
    }
    // ENOBUFS: the kernel dropped messages it could not deliver; it counts them itself.
    if (errno == ENOBUFS || errno == EINTR) continue;
    if (errno == EAGAIN || errno == EWOULDBLOCK) return;
    fail("reading NFQUEUE " + std::to_string(number_));
  }
}

void NetfilterQueue::accept(std::uint32_t packet_id) {
  nfq_set_verdict(queue_, packet_id, NF_ACCEPT, 0, nullptr);
}

void NetfilterQueue::drop(std::uint32_t packet_id) {
  nfq_set_verdict(queue_, packet_id, NF_DROP, 0, nullptr);
}

QueueDrops NetfilterQueue::drops() const {
  // One line per queue: number, peer port id, total, copy mode, copy range, queue dropped,
  // user dropped, id sequence, 1.
  std::ifstream table("/proc/net/netfilter/nfnetlink_queue");
  std::string line;
  while (std::getline(table, line)) {
    std::istringstream fields(line);
    unsigned queue = 0;
    unsigned long long ignored = 0;
    QueueDrops drops;
    if (fields >> queue >> ignored >> ignored >> ignored >> ignored >> drops.queue_full >>
            drops.undelivered &&
        queue == number_) {
      return drops;
    }
  }
  return {};
}

}  // namespace uavslam::net
