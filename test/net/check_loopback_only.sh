#!/bin/sh
# The network rule, measured on the wire: runs a command while tcpdump watches the machine's real
# interface and the loopback interface, then fails if any DDS packet went out through the real
# one. A DDS packet is: UDP whose payload starts with the RTPS magic "RTPS" (any domain, any
# port), anything sent to the discovery multicast group 239.255.0.1, or UDP on the default DDS
# ports 7400-7500 (IPv4 or IPv6). Counts for both interfaces are printed; the loopback count shows
# the command really talked over UDP (shared-memory traffic never appears on any interface).
#
#   sudo test/net/check_loopback_only.sh [-i IFACE] -- COMMAND [ARG...]
#   sudo test/net/check_loopback_only.sh -- build/test/unit/dds/test_dds_profiles
#
# IFACE defaults to the interface of the default route. Needs root for tcpdump, so it is not part
# of ctest. Exit status: 1 if DDS traffic reached IFACE, else the command's own status.
set -eu

usage() {
  echo "usage: $0 [-i IFACE] -- COMMAND [ARG...]" >&2
  exit 2
}

iface=$(ip route show default 2>/dev/null | awk '{print $5; exit}')
iface=${iface:-eth0}
while [ $# -gt 0 ]; do
  case $1 in
    -i) [ $# -ge 2 ] || usage; iface=$2; shift 2 ;;
    --) shift; break ;;
    -*) usage ;;
    *) break ;;
  esac
done
[ $# -gt 0 ] || usage
command -v tcpdump >/dev/null || { echo "$0: needs tcpdump (apt-get install tcpdump)" >&2; exit 2; }

dds_filter='(ip and udp and udp[8:4] = 0x52545053) or (dst host 239.255.0.1)'
dds_filter="$dds_filter or (udp and portrange 7400-7500)"
rtps_filter='ip and udp and udp[8:4] = 0x52545053'

dir=$(mktemp -d)
real_pid=''
lo_pid=''
cleanup() {
  for pid in $real_pid $lo_pid; do kill -INT "$pid" 2>/dev/null || true; done
  rm -rf "$dir"
}
trap cleanup EXIT INT TERM

tcpdump -i "$iface" -n -U -w "$dir/real.pcap" "$dds_filter" 2>"$dir/real.err" &
real_pid=$!
tcpdump -i lo -n -U -w "$dir/lo.pcap" "$rtps_filter" 2>"$dir/lo.err" &
lo_pid=$!

# Both captures must be running before the command starts (bounded wait).
tries=0
until grep -q "listening on" "$dir/real.err" && grep -q "listening on" "$dir/lo.err"; do
  tries=$((tries + 1))
  if [ $tries -gt 100 ]; then
    echo "$0: tcpdump did not start:" >&2
    cat "$dir/real.err" "$dir/lo.err" >&2
    exit 2
  fi
  sleep 0.1
done

status=0
"$@" || status=$?

# -U writes every packet as it comes; SIGINT makes tcpdump close its file and exit.
kill -INT "$real_pid" "$lo_pid"
wait "$real_pid" 2>/dev/null || true
wait "$lo_pid" 2>/dev/null || true
real_pid=''
lo_pid=''

count() { tcpdump -n -r "$1" 2>/dev/null | wc -l; }
real_count=$(count "$dir/real.pcap")
lo_count=$(count "$dir/lo.pcap")
echo "check_loopback_only: DDS packets on $iface: $real_count; RTPS packets on lo: $lo_count;" \
  "command exit status $status"
if [ "$real_count" -ne 0 ]; then
  echo "check_loopback_only: DDS traffic left through $iface (first packets):" >&2
  tcpdump -n -r "$dir/real.pcap" 2>/dev/null | head -20 >&2
  exit 1
fi
exit "$status"
