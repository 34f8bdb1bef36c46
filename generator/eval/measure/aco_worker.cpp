#include "watergen/eval/measure/aco_worker.h"

#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <future>
#include <set>

#include <nlohmann/json.hpp>

#include "watergen/eval/measure/scratch_directory.h"
#include "watergen/pipeline/output/output_writer.h"
#include "watergen/pipeline/output/safe_read.h"
#include "watergen/toolchain/child_process.h"

namespace watergen {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

constexpr const char* kPrefix = "watergen-aco-";

// A file of the job directory, created or truncated in place; never through a link (a job
// directory's names are the protocol's, whoever put a link there).
bool write_bytes(const fs::path& file, const void* data, size_t size) {
    const int fd =
        ::open(file.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, 0600);
    if (fd < 0) return false;
    const char* at = static_cast<const char*>(data);
    bool ok = true;
    for (size_t left = size; ok && left > 0;) {
        const ssize_t n = ::write(fd, at, left);
        if (n < 0 && errno == EINTR) continue;
        ok = n > 0;
        if (ok) at += n, left -= static_cast<size_t>(n);
    }
    return ::close(fd) == 0 && ok;
}

// The job's and the answer's files: written by this protocol, in a directory of its own.
constexpr size_t kMaxJobFileBytes = size_t(256) << 20;

std::optional<std::string> read_text(const fs::path& file) {
    return read_regular_file(file, kMaxJobFileBytes).bytes;
}

// Pipeline i's files: <i>.vert.spv, <i>.frag.spv (and a tessellated mesh's <i>.tesc.spv,
// <i>.tese.spv) and their .reflect.json.
fs::path file_of(const fs::path& dir, size_t i, const char* suffix) {
    return dir / (std::to_string(i) + suffix);
}

} // namespace

std::string write_aco_job(const fs::path& dir, const std::vector<AcoPipelineSource>& sources,
                          bool disassembly) {
    json job = json::object();
    job["disassembly"] = disassembly;
    job["pipelines"] = json::array();
    for (size_t i = 0; i < sources.size(); ++i) {
        const AcoPipelineSource& s = sources[i];
        const std::string vr = reflection_to_json(s.vertex_reflection);
        const std::string fr = reflection_to_json(s.fragment_reflection);
        if (!write_bytes(file_of(dir, i, ".vert.spv"), s.vertex.data(), s.vertex.size() * 4) ||
            !write_bytes(file_of(dir, i, ".frag.spv"), s.fragment.data(), s.fragment.size() * 4) ||
            !write_bytes(file_of(dir, i, ".vert.reflect.json"), vr.data(), vr.size()) ||
            !write_bytes(file_of(dir, i, ".frag.reflect.json"), fr.data(), fr.size()))
            return "cannot write the job's files in " + dir.string();
        if (!s.tess_control.empty()) {
            const std::string cr = reflection_to_json(s.tess_control_reflection);
            const std::string er = reflection_to_json(s.tess_evaluation_reflection);
            if (!write_bytes(file_of(dir, i, ".tesc.spv"), s.tess_control.data(),
                             s.tess_control.size() * 4) ||
                !write_bytes(file_of(dir, i, ".tese.spv"), s.tess_evaluation.data(),
                             s.tess_evaluation.size() * 4) ||
                !write_bytes(file_of(dir, i, ".tesc.reflect.json"), cr.data(), cr.size()) ||
                !write_bytes(file_of(dir, i, ".tese.reflect.json"), er.data(), er.size()))
                return "cannot write the job's files in " + dir.string();
        }
        json spec = json::object();
        for (const auto& [id, value] : s.specialization)
            spec[std::to_string(id)] = value;
        json entry = {{"name", s.name}, {"specialization", spec}, {"format", s.format}};
        if (s.geometry)
            entry["geometry"] = {{"attribute_sizes", s.geometry->attribute_sizes},
                                 {"points", s.geometry->points},
                                 {"additive_blend", s.geometry->additive_blend},
                                 {"patch_control_points", s.geometry->patch_control_points}};
        entry["tessellated"] = !s.tess_control.empty();
        job["pipelines"].push_back(entry);
    }
    const std::string text = job.dump(1);
    if (!write_bytes(dir / "job.json", text.data(), text.size()))
        return "cannot write " + (dir / "job.json").string();
    return "";
}

namespace {

std::optional<std::vector<uint32_t>> read_spirv(const fs::path& file) {
    const auto bytes = read_text(file);
    if (!bytes || bytes->size() % 4 != 0) return std::nullopt;
    std::vector<uint32_t> words(bytes->size() / 4);
    std::copy(bytes->begin(), bytes->end(), reinterpret_cast<char*>(words.data()));
    return words;
}

// Pipeline i of the job, its entry parsed by parse_aco_job, its files read; "" or what is wrong.
std::string read_source(const fs::path& dir, size_t i, AcoJobPipeline&& entry,
                        AcoPipelineSource& s) {
    s.name = std::move(entry.name);
    s.specialization = std::move(entry.specialization);
    s.format = entry.format;
    s.geometry = std::move(entry.geometry);
    auto vs = read_spirv(file_of(dir, i, ".vert.spv"));
    auto fs_ = read_spirv(file_of(dir, i, ".frag.spv"));
    const auto vr = read_text(file_of(dir, i, ".vert.reflect.json"));
    const auto fr = read_text(file_of(dir, i, ".frag.reflect.json"));
    if (!vs || !fs_ || !vr || !fr) return "pipeline " + std::to_string(i) + ": missing files";
    s.vertex = std::move(*vs);
    s.fragment = std::move(*fs_);
    std::string error;
    auto v = reflection_from_json(*vr, &error);
    auto f = reflection_from_json(*fr, &error);
    if (!v || !f) return "pipeline " + std::to_string(i) + ": reflection: " + error;
    s.vertex_reflection = std::move(*v);
    s.fragment_reflection = std::move(*f);
    if (entry.tessellated) {
        auto cs = read_spirv(file_of(dir, i, ".tesc.spv"));
        auto es = read_spirv(file_of(dir, i, ".tese.spv"));
        const auto cr = read_text(file_of(dir, i, ".tesc.reflect.json"));
        const auto er = read_text(file_of(dir, i, ".tese.reflect.json"));
        if (!cs || !es || !cr || !er)
            return "pipeline " + std::to_string(i) + ": missing tessellation files";
        auto c = reflection_from_json(*cr, &error);
        auto e = reflection_from_json(*er, &error);
        if (!c || !e) return "pipeline " + std::to_string(i) + ": reflection: " + error;
        s.tess_control = std::move(*cs);
        s.tess_evaluation = std::move(*es);
        s.tess_control_reflection = std::move(*c);
        s.tess_evaluation_reflection = std::move(*e);
    }
    return "";
}

json stage_json(const AcoStageStatistics& st) {
    json loops = json::array();
    for (const AsmLoop& l : st.loops)
        loops.push_back({l.first, l.last, l.instructions, l.depth});
    return {{"stage", st.stage},
            {"executable", st.executable},
            {"subgroup_size", st.subgroup_size},
            {"values", st.values},
            {"loops", loops},
            {"has_disassembly", st.has_disassembly}};
}

AcoStageStatistics stage_from_json(const json& j) {
    AcoStageStatistics st;
    st.stage = j.at("stage").get<std::string>();
    st.executable = j.at("executable").get<std::string>();
    st.subgroup_size = j.at("subgroup_size").get<uint32_t>();
    st.values = j.at("values").get<std::map<std::string, double>>();
    for (const json& l : j.at("loops"))
        st.loops.push_back({l[0].get<uint32_t>(), l[1].get<uint32_t>(), l[2].get<uint32_t>(),
                            l[3].get<uint32_t>()});
    st.has_disassembly = j.at("has_disassembly").get<bool>();
    return st;
}

// The worker's result.json read back into `run`.
void read_result(const fs::path& dir, AcoTargetRun& run) {
    const auto text = read_text(dir / "result.json");
    if (!text) {
        run.error = "the worker wrote no result.json";
        return;
    }
    try {
        const json r = json::parse(*text);
        run.device = r.at("device").get<std::string>();
        run.driver = r.at("driver").get<std::string>();
        for (const json& p : r.at("pipelines")) {
            AcoPipelineStatistics s;
            s.name = p.at("name").get<std::string>();
            s.error = p.at("error").get<std::string>();
            s.unsupported = p.at("unsupported").get<bool>();
            for (const json& st : p.at("stages"))
                s.stages.push_back(stage_from_json(st));
            run.pipelines.push_back(std::move(s));
        }
    } catch (const json::exception& e) {
        run.error = std::string("result.json: ") + e.what();
    }
}

AcoTargetRun run_family(const GpuTarget& target, const fs::path& icd,
                        const std::vector<AcoPipelineSource>& sources, const fs::path& scratch,
                        const fs::path& worker) {
    AcoTargetRun run;
    run.target = target;
    ScratchDirectory dir(scratch, kPrefix);
    if (!dir.error().empty()) {
        run.error = dir.error();
        return run;
    }
    run.error = write_aco_job(dir.path(), sources, target.disassembly);
    if (!run.error.empty()) return run;
    const std::vector<std::string> argv = {worker.string(), "gpu-worker", dir.path().string()};
    // Mesa's shader cache off: every statistic comes from a compile, and nothing is written
    // under the user's home. The loader reads VK_DRIVER_FILES before VK_ICD_FILENAMES and adds
    // VK_ADD_DRIVER_FILES: a caller's (a CI that pins lavapipe) must not choose the worker's.
    const std::vector<std::string> env = {"VK_ICD_FILENAMES=" + icd.string(),
                                          "VK_DRIVER_FILES=" + icd.string(), "VK_ADD_DRIVER_FILES",
                                          "RADV_FORCE_FAMILY=" + target.family,
                                          "MESA_SHADER_CACHE_DISABLE=true"};
    const std::string failure = run_child_process(argv, dir.path(), env);
    if (failure.find("exit status 3") != std::string::npos) {
        run.no_device = true;
        run.error = "RADV's null device for " + target.name + " (" + target.family +
                    ") did not open: " + failure;
        return run;
    }
    if (!failure.empty()) {
        const auto at = read_text(dir.path() / "compiling.txt");
        run.error = target.name + " (" + target.family + "): the driver's worker failed" +
                    (at ? " compiling " + *at : std::string()) + ": " + failure;
        return run;
    }
    read_result(dir.path(), run);
    if (run.ok() && run.pipelines.size() != sources.size())
        run.error = "result.json holds " + std::to_string(run.pipelines.size()) +
                    " pipelines, not " + std::to_string(sources.size());
    return run;
}

} // namespace

std::optional<fs::path> radeon_icd() {
    if (const char* named = std::getenv("WATERGEN_RADEON_ICD")) {
        std::error_code ec;
        if (fs::is_regular_file(named, ec)) return fs::path(named);
        return std::nullopt;
    }
    for (const char* dir :
         {"/usr/share/vulkan/icd.d", "/etc/vulkan/icd.d", "/usr/local/share/vulkan/icd.d"}) {
        std::error_code ec;
        for (const auto& e : fs::directory_iterator(dir, ec)) {
            const std::string name = e.path().filename().string();
            if (name.rfind("radeon_icd.", 0) == 0 && e.path().extension() == ".json")
                return e.path();
        }
    }
    return std::nullopt;
}

std::vector<AcoTargetRun> compile_on_targets(const std::vector<GpuTarget>& targets,
                                             const std::vector<AcoPipelineSource>& sources,
                                             const fs::path& scratch, unsigned workers,
                                             const fs::path& worker) {
    std::vector<AcoTargetRun> out(targets.size());
    const auto icd = radeon_icd();
    if (!icd) {
        for (size_t i = 0; i < targets.size(); ++i) {
            out[i].target = targets[i];
            out[i].no_device = true;
            out[i].error = std::getenv("WATERGEN_RADEON_ICD")
                               ? std::string("WATERGEN_RADEON_ICD names no file: ") +
                                     std::getenv("WATERGEN_RADEON_ICD")
                               : "RADV's null device needs Mesa's radeon Vulkan driver "
                                 "(apt-get install mesa-vulkan-drivers: radeon_icd.*.json in "
                                 "/usr/share/vulkan/icd.d); none is installed";
        }
        return out;
    }
    sweep_stale_scratch(scratch, kPrefix);
    // One run per family; an alias waits for its ISA's.
    std::vector<std::string> families;
    for (const auto& t : targets)
        if (std::find(families.begin(), families.end(), t.family) == families.end())
            families.push_back(t.family);
    std::map<std::string, AcoTargetRun> by_family;
    const size_t batch = std::max(workers, 1u);
    for (size_t begin = 0; begin < families.size(); begin += batch) {
        std::vector<std::pair<std::string, std::future<AcoTargetRun>>> running;
        for (size_t f = begin; f < std::min(families.size(), begin + batch); ++f) {
            const auto t = std::find_if(targets.begin(), targets.end(), [&](const GpuTarget& g) {
                return g.family == families[f];
            });
            running.emplace_back(families[f], std::async(std::launch::async, [&, t] {
                                     return run_family(*t, *icd, sources, scratch, worker);
                                 }));
        }
        for (auto& [family, run] : running)
            by_family[family] = run.get();
    }
    for (size_t i = 0; i < targets.size(); ++i) {
        out[i] = by_family[targets[i].family];
        out[i].target = targets[i];
    }
    return out;
}

namespace {

int aco_worker(const fs::path& dir) {
    const auto text = read_text(dir / "job.json");
    std::string error = "no job.json";
    std::optional<AcoJob> job = text ? parse_aco_job(*text, &error) : std::nullopt;
    if (!job) {
        std::fprintf(stderr, "watergen: error: %s/job.json: %s\n", dir.string().c_str(),
                     error.c_str());
        return 2;
    }
    const auto device = AcoDevice::open(&error, job->disassembly);
    if (!device) {
        std::fprintf(stderr, "watergen: error: %s\n", error.c_str());
        return 3;
    }
    json result = {{"device", device->name()}, {"driver", device->driver_info()}};
    result["pipelines"] = json::array();
    for (size_t i = 0; i < job->pipelines.size(); ++i) {
        AcoPipelineSource source;
        error = read_source(dir, i, std::move(job->pipelines[i]), source);
        if (!error.empty()) {
            std::fprintf(stderr, "watergen: error: %s: %s\n", dir.string().c_str(), error.c_str());
            return 2;
        }
        // Named before the driver sees it: a crash inside the compiler leaves this behind.
        write_bytes(dir / "compiling.txt", source.name.data(), source.name.size());
        const AcoPipelineStatistics s = device->compile(source);
        json stages = json::array();
        for (const auto& st : s.stages)
            stages.push_back(stage_json(st));
        result["pipelines"].push_back({{"name", s.name},
                                       {"error", s.error},
                                       {"unsupported", s.unsupported},
                                       {"stages", stages}});
    }
    return write_file_atomically(dir / "result.json", result.dump(1)) ? 1 : 0;
}

} // namespace

int run_aco_worker(const fs::path& dir) {
    try {
        return aco_worker(dir);
    } catch (const std::exception& e) { // a job.json of another shape
        std::fprintf(stderr, "watergen: error: %s/job.json: %s\n", dir.string().c_str(), e.what());
        return 2;
    }
}

} // namespace watergen
