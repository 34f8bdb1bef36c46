// Writes a set of files so that a reader never sees a half-written result.
#pragma once

#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace watergen {

// A name that stays inside the directory it is written under: relative, components separated
// by single '/', none empty, "." or "..", no NUL. Checked before anything is written.
bool is_plain_relative_path(const std::string& path);

// Writes `files` (relative path -> contents) under `root`, a fresh directory. A name that is not
// a plain relative path fails before anything is written.
std::optional<std::string> write_tree(const std::filesystem::path& root,
                                      const std::map<std::string, std::string>& files);

// Writes `files` into a fresh sibling of `dir` (write_tree), then replaces `dir` with it by
// rename. On failure `dir` is left as it was and the error names the path.
std::optional<std::string>
write_directory_atomically(const std::filesystem::path& dir,
                           const std::map<std::string, std::string>& files);

// A fresh, empty staging directory beside `dir` for writers that produce files themselves;
// publish it with commit_directory(staging, dir), or remove it on failure.
std::filesystem::path make_staging_directory(const std::filesystem::path& dir, std::string* error);
// make_staging_directory with `files` written into it (write_tree); on failure "" and the error
// in `error`, nothing left behind.
std::filesystem::path write_staged_tree(const std::filesystem::path& dir,
                                        const std::map<std::string, std::string>& files,
                                        std::string* error);
// Replaces `dir` with `staging` by rename; the old `dir` stays complete until then.
std::optional<std::string> commit_directory(const std::filesystem::path& staging,
                                            const std::filesystem::path& dir);
// Puts `staging` in the place of `dir` in one step: renameat2(RENAME_EXCHANGE) where the file
// system has it (whenever the process dies, `dir` holds the old tree or the new one), else
// commit_directory().
std::optional<std::string> swap_directory_into_place(const std::filesystem::path& staging,
                                                     const std::filesystem::path& dir);
// Removes the staging directories beside `dir` that killed processes left.
void remove_stale_staging(const std::filesystem::path& dir);
// Removes the tree a commit replaced (now under a staging name); one that cannot be removed is
// reported on stderr, "watergen: warning: cannot remove the replaced <path>: <why>; remove it by
// hand", rather than left without a word.
void remove_replaced_tree(const std::filesystem::path& old);

// A new directory <root>/<prefix>XXXXXX of this process alone (mkdtemp: a name no other
// process, in any PID namespace, has or gets); "" and the error in `error` when it cannot be
// made. The caller removes it.
std::filesystem::path make_unique_directory(const std::filesystem::path& root,
                                            const std::string& prefix, std::string* error);

// Creates `path` and writes `contents` to it; never through an existing name or a link
// (O_EXCL | O_NOFOLLOW). The error names the path and carries errno's text.
std::optional<std::string> write_new_file(const std::filesystem::path& path,
                                          const std::string& contents);

// Writes one file through a temporary in the same directory and a rename.
std::optional<std::string> write_file_atomically(const std::filesystem::path& path,
                                                 const std::string& contents);
// The same for contents made piece by piece: `produce` hands each piece to its argument.
using ProduceText = std::function<void(const std::function<void(std::string_view)>&)>;
std::optional<std::string> write_file_atomically(const std::filesystem::path& path,
                                                 const ProduceText& produce);

} // namespace watergen
