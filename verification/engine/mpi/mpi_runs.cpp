#include "engine/mpi/mpi_runs.hpp"

// The C API only (the deprecated C++ bindings of mpi.h do not compile without warnings).
#define OMPI_SKIP_MPICXX 1
#define MPICH_SKIP_MPICXX 1
#include <mpi.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <csignal>
#include <deque>
#include <exception>
#include <filesystem>
#include <map>
#include <mutex>
#include <stdexcept>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "dem/run/interrupt.hpp"
#include "dem/run/output_files.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace ver::mpi {

namespace {

enum Tag : int { kRun = 1, kReply = 2, kStop = 3, kInterrupt = 4 };
constexpr auto kIdle = std::chrono::milliseconds(1);  // polling period of an idle rank (no busy wait)

void check(int rc, const char* what) {
  if (rc != MPI_SUCCESS) throw std::runtime_error(fmt::format("MPI: {} failed ({})", what, rc));
}

// Messages are CBOR: doubles travel as IEEE binary64 (bit for bit), NaN included.
void send(const json& j, int dest, int tag) {
  const std::vector<std::uint8_t> bytes = json::to_cbor(j);
  check(MPI_Send(bytes.data(), static_cast<int>(bytes.size()), MPI_BYTE, dest, tag, MPI_COMM_WORLD), "MPI_Send");
}

/// A waiting message from `source` (any if MPI_ANY_SOURCE) with `tag` (any if MPI_ANY_TAG), if any.
std::optional<std::pair<MPI_Status, json>> receive(int source, int tag) {
  int flag = 0;
  MPI_Status st;
  check(MPI_Iprobe(source, tag, MPI_COMM_WORLD, &flag, &st), "MPI_Iprobe");
  if (!flag) return std::nullopt;
  int n = 0;
  check(MPI_Get_count(&st, MPI_BYTE, &n), "MPI_Get_count");
  std::vector<std::uint8_t> bytes(static_cast<std::size_t>(n));
  check(MPI_Recv(bytes.data(), n, MPI_BYTE, st.MPI_SOURCE, st.MPI_TAG, MPI_COMM_WORLD, MPI_STATUS_IGNORE), "MPI_Recv");
  return std::pair{st, bytes.empty() ? json() : json::from_cbor(bytes)};
}

json probes_json(const std::map<std::string, std::optional<double>>& probes) {
  json p = json::object();
  for (const auto& [k, v] : probes) p[k] = v ? json(*v) : json(nullptr);
  return p;
}

std::map<std::string, std::optional<double>> probes_of(const json& p) {
  std::map<std::string, std::optional<double>> out;
  for (const auto& [k, v] : p.items()) out[k] = v.is_null() ? std::nullopt : std::optional<double>(v.get<double>());
  return out;
}

}  // namespace

// ---- the session ----

Session::Session(int* argc, char*** argv) {
  int provided = 0;
  check(MPI_Init_thread(argc, argv, MPI_THREAD_SERIALIZED, &provided), "MPI_Init_thread");
  MPI_Comm_rank(MPI_COMM_WORLD, &rank_);
  MPI_Comm_size(MPI_COMM_WORLD, &size_);
  if (size_ > 1 && provided < MPI_THREAD_SERIALIZED) {
    fmt::print(stderr, "error: this MPI library does not provide MPI_THREAD_SERIALIZED\n");
    MPI_Abort(MPI_COMM_WORLD, 2);
  }
}

Session::~Session() { MPI_Finalize(); }

// ---- rank 0 ----

struct Batch {
  const std::vector<RunRequest>* reqs = nullptr;
  const RunDone* done = nullptr;
  std::size_t remaining = 0;
  std::exception_ptr error;
};

struct Item {
  Batch* batch = nullptr;
  std::size_t index = 0;  // in the batch
  std::uint64_t seq = 0;  // submission order: ties in cost go in this order
  const RunRequest& req() const { return (*batch->reqs)[index]; }
};

struct Distributor::State {
  int jobs = 1, ranks = 1;
  std::mutex m;
  std::condition_variable cv;       // the queue changed or a batch finished
  std::vector<Item> queue;          // waiting runs
  std::uint64_t seq = 0, next_id = 0;
  bool stop = false;
  std::vector<std::thread> local;   // rank 0's own run slots
  std::thread dispatcher;           // the only thread that calls MPI while the distributor lives
  std::map<std::uint64_t, Item> remote;  // id → run out on another rank
  std::vector<int> busy;            // runs out per rank
  bool interrupt_sent = false;

  /// The longest waiting run (lock held); false if none.
  bool pop(Item& out) {
    if (queue.empty()) return false;
    auto best = std::max_element(queue.begin(), queue.end(), [&](const Item& a, const Item& b) {
      const double ca = a.req().cost, cb = b.req().cost;
      return ca != cb ? ca < cb : a.seq > b.seq;
    });
    out = *best;
    queue.erase(best);
    return true;
  }

  /// Calls the batch's done() and counts the run as finished.
  void finish(const Item& it, RunReply& reply) {
    try {
      (*it.batch->done)(it.index, reply);
    } catch (...) {
      std::lock_guard<std::mutex> l(m);
      if (!it.batch->error) it.batch->error = std::current_exception();
    }
    std::lock_guard<std::mutex> l(m);
    --it.batch->remaining;
    cv.notify_all();
  }

  void local_slot() {
    for (;;) {
      Item it;
      {
        std::unique_lock<std::mutex> l(m);
        cv.wait(l, [&] { return stop || !queue.empty(); });
        if (!pop(it)) return;  // stop and nothing left
      }
      RunReply r;
      try {
        r = run_here(it.req(), it.req().out);
      } catch (const std::exception& e) {
        r = {"error", e.what(), 0.0, {}};
      }
      finish(it, r);
    }
  }

  void dispatch() {
    for (;;) {
      bool active = false;
      // A signal on rank 0 goes to every rank: their runs stop at the next step.
      if (dem::interrupt_signal() != 0 && !interrupt_sent) {
        for (int r = 1; r < ranks; ++r) send(json::object(), r, kInterrupt);
        interrupt_sent = true;
      }
      // Free slots on the other ranks get the longest waiting runs.
      for (int r = 1; r < ranks; ++r)
        while (busy[static_cast<std::size_t>(r)] < jobs) {
          Item it;
          {
            std::lock_guard<std::mutex> l(m);
            if (!pop(it)) break;
          }
          const std::uint64_t id = next_id++;
          send({{"id", id}, {"case", it.req().case_file.string()}, {"sets", it.req().sets}, {"files", !it.req().out.empty()}},
               r, kRun);
          remote.emplace(id, it);
          ++busy[static_cast<std::size_t>(r)];
          active = true;
        }
      while (auto msg = receive(MPI_ANY_SOURCE, kReply)) {
        active = true;
        const json& j = msg->second;
        const auto node = remote.find(j.at("id").get<std::uint64_t>());
        const Item it = node->second;
        remote.erase(node);
        --busy[static_cast<std::size_t>(msg->first.MPI_SOURCE)];
        RunReply r{j.at("status").get<std::string>(), j.at("message").get<std::string>(), j.at("eps").get<double>(),
                   probes_of(j.at("probes")), j.value("seconds_per_step", 0.0)};
        try {  // the run folder, as the run would have written it here
          if (!it.req().out.empty() && j.contains("files")) {
            fs::remove_all(it.req().out);
            fs::create_directories(it.req().out);
            for (const auto& f : j.at("files")) {
              const fs::path file = it.req().out / f.at("path").get<std::string>();
              fs::create_directories(file.parent_path());
              const auto& bytes = f.at("content").get_binary();
              dem::write_file_atomic(file, std::string(bytes.begin(), bytes.end()), false);
            }
          }
        } catch (const std::exception& e) {
          r = {"error", fmt::format("writing the run folder {}: {}", it.req().out.string(), e.what()), 0.0, {}};
        }
        finish(it, r);
      }
      {
        std::lock_guard<std::mutex> l(m);
        if (stop && queue.empty() && remote.empty()) break;
      }
      if (!active) std::this_thread::sleep_for(kIdle);
    }
    for (int r = 1; r < ranks; ++r) send(json::object(), r, kStop);
  }
};

Distributor::Distributor(int jobs) : st_(std::make_unique<State>()) {
  st_->jobs = std::max(1, jobs);
  MPI_Comm_size(MPI_COMM_WORLD, &st_->ranks);
  st_->busy.assign(static_cast<std::size_t>(st_->ranks), 0);
  for (int t = 0; t < st_->jobs; ++t) st_->local.emplace_back([s = st_.get()] { s->local_slot(); });
  st_->dispatcher = std::thread([s = st_.get()] {
    try {
      s->dispatch();
    } catch (const std::exception& e) {  // MPI failed: nothing sensible is left to do
      fmt::print(stderr, "error: rank 0: {}\n", e.what());
      MPI_Abort(MPI_COMM_WORLD, 3);
    }
  });
  set_run_distributor(this);
}

Distributor::~Distributor() {
  set_run_distributor(nullptr);
  {
    std::lock_guard<std::mutex> l(st_->m);
    st_->stop = true;
  }
  st_->cv.notify_all();
  for (auto& t : st_->local) t.join();
  st_->dispatcher.join();
}

void Distributor::run(const std::vector<RunRequest>& reqs, const RunDone& done) {
  Batch b{&reqs, &done, reqs.size(), nullptr};
  std::unique_lock<std::mutex> l(st_->m);
  for (std::size_t i = 0; i < reqs.size(); ++i) st_->queue.push_back({&b, i, st_->seq++});
  st_->cv.notify_all();
  st_->cv.wait(l, [&] { return b.remaining == 0; });
  if (b.error) std::rethrow_exception(b.error);
}

// ---- ranks > 0 ----

int serve(int jobs) {
  int rank = 0;
  MPI_Comm_rank(MPI_COMM_WORLD, &rank);
  std::mutex m;
  std::condition_variable cv;
  std::deque<json> todo, replies;
  bool stop = false;
  std::vector<std::thread> slots;
  for (int t = 0; t < std::max(1, jobs); ++t)
    slots.emplace_back([&] {
      for (;;) {
        json req;
        {
          std::unique_lock<std::mutex> l(m);
          cv.wait(l, [&] { return stop || !todo.empty(); });
          if (todo.empty()) return;
          req = std::move(todo.front());
          todo.pop_front();
        }
        const std::uint64_t id = req.at("id").get<std::uint64_t>();
        json reply = {{"id", id}};
        // A run folder of its own, in this node's temporary folder, deleted once sent.
        const fs::path dir = req.at("files").get<bool>()
                                 ? fs::temp_directory_path() / fmt::format("dem2d-rank{}-{}-{}", rank, ::getpid(), id)
                                 : fs::path();
        try {
          const RunRequest r{req.at("case").get<std::string>(), req.at("sets").get<std::vector<std::string>>(), dir, 0.0};
          const RunReply out = run_here(r, dir);
          reply["status"] = out.status;
          reply["message"] = out.message;
          reply["eps"] = out.eps;
          reply["seconds_per_step"] = out.seconds_per_step;
          reply["probes"] = probes_json(out.probes);
          if (!dir.empty() && fs::exists(dir)) {
            json files = json::array();
            std::vector<fs::path> paths;
            for (const auto& e : fs::recursive_directory_iterator(dir))
              if (e.is_regular_file()) paths.push_back(e.path());
            std::sort(paths.begin(), paths.end());
            for (const auto& p : paths) {
              const std::string content = dem::read_file(p);
              files.push_back({{"path", fs::relative(p, dir).string()},
                               {"content", json::binary(std::vector<std::uint8_t>(content.begin(), content.end()))}});
            }
            reply["files"] = files;
          }
        } catch (const std::exception& e) {
          reply["status"] = "error";
          reply["message"] = fmt::format("rank {}: {}", rank, e.what());
          reply["eps"] = 0.0;
          reply["probes"] = json::object();
        }
        std::error_code ec;
        if (!dir.empty()) fs::remove_all(dir, ec);
        std::lock_guard<std::mutex> l(m);
        replies.push_back(std::move(reply));
      }
    });
  int code = 0;
  try {
    for (bool done = false; !done;) {
      bool active = false;
      while (auto msg = receive(0, MPI_ANY_TAG)) {
        active = true;
        const int tag = msg->first.MPI_TAG;
        if (tag == kRun) {
          std::lock_guard<std::mutex> l(m);
          todo.push_back(std::move(msg->second));
          cv.notify_one();
        } else if (tag == kInterrupt) {
          dem::set_interrupt_signal(SIGTERM);
        } else if (tag == kStop) {
          done = true;
          break;
        }
      }
      for (;;) {
        json reply;
        {
          std::lock_guard<std::mutex> l(m);
          if (replies.empty()) break;
          reply = std::move(replies.front());
          replies.pop_front();
        }
        send(reply, 0, kReply);
        active = true;
      }
      if (!active && !done) std::this_thread::sleep_for(kIdle);
    }
  } catch (const std::exception& e) {
    fmt::print(stderr, "error: rank {}: {}\n", rank, e.what());
    MPI_Abort(MPI_COMM_WORLD, 3);
  }
  {
    std::lock_guard<std::mutex> l(m);
    stop = true;
  }
  cv.notify_all();
  for (auto& t : slots) t.join();
  return code;
}

}  // namespace ver::mpi
