#include "radchain/plugin_host.hpp"

#include "radchain/error.hpp"

#include <boost/dll/runtime_symbol_info.hpp>
#include <boost/dll/shared_library.hpp>
#include <dlfcn.h>
#include <elf.h>
#include <fcntl.h>
#include <sys/mman.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <deque>
#include <bit>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <iostream>
#include <map>
#include <mutex>
#include <optional>
#include <set>
#include <sstream>

namespace radchain {
namespace fs = std::filesystem;

namespace {

// The library's radchain_plugin_abi_version read from the file itself (its ELF dynamic symbol table), before
// dlopen runs any of its static constructors. Found: the number; the file is a well-formed ELF64 without
// the symbol: 0 (not a plugin); anything else (another ELF class, a malformed or huge file): nullopt, and the
// loader's own checks decide.
// The file mapped read-only: only the pages of the headers and the dynamic symbol table are read (a plugin with
// debug information is megabytes; reading every plugin whole was a fifth of a 1,000-file catalogue).
class MappedFile {
 public:
  explicit MappedFile(const std::string& path) {
    const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) return;
    struct stat st {};
    if (::fstat(fd, &st) == 0 && S_ISREG(st.st_mode) && st.st_size > 0) {
      void* p = ::mmap(nullptr, static_cast<std::size_t>(st.st_size), PROT_READ, MAP_PRIVATE, fd, 0);
      if (p != MAP_FAILED) data_ = static_cast<const char*>(p), size_ = static_cast<std::size_t>(st.st_size);
    }
    ::close(fd);
  }
  ~MappedFile() {
    if (data_) ::munmap(const_cast<char*>(data_), size_);
  }
  MappedFile(const MappedFile&) = delete;
  MappedFile& operator=(const MappedFile&) = delete;
  const char* data() const { return data_; }
  std::size_t size() const { return size_; }

 private:
  const char* data_ = nullptr;
  std::size_t size_ = 0;
};

std::optional<std::uint32_t> abi_in_file(const std::string& path) {
  const MappedFile bytes(path);
  const std::uint64_t size = bytes.size();
  if (!bytes.data() || size < sizeof(Elf64_Ehdr) || size > (std::uint64_t{1} << 30)) return std::nullopt;
  auto fits = [&](std::uint64_t offset, std::uint64_t length) { return offset <= size && length <= size - offset; };
  Elf64_Ehdr eh;
  std::memcpy(&eh, bytes.data(), sizeof eh);
  if (std::memcmp(eh.e_ident, ELFMAG, SELFMAG) != 0 || eh.e_ident[EI_CLASS] != ELFCLASS64 ||
      eh.e_ident[EI_DATA] != (std::endian::native == std::endian::little ? ELFDATA2LSB : ELFDATA2MSB) ||
      eh.e_shentsize != sizeof(Elf64_Shdr) || !fits(eh.e_shoff, std::uint64_t{eh.e_shnum} * sizeof(Elf64_Shdr)))
    return std::nullopt;
  auto section = [&](std::size_t i) {
    Elf64_Shdr sh;
    std::memcpy(&sh, bytes.data() + eh.e_shoff + i * sizeof(Elf64_Shdr), sizeof sh);
    return sh;
  };
  for (std::size_t i = 0; i < eh.e_shnum; ++i) {
    const Elf64_Shdr symbols = section(i);
    if (symbols.sh_type != SHT_DYNSYM) continue;
    if (symbols.sh_link >= eh.e_shnum || !fits(symbols.sh_offset, symbols.sh_size)) return std::nullopt;
    const Elf64_Shdr names = section(symbols.sh_link);
    if (!fits(names.sh_offset, names.sh_size)) return std::nullopt;
    for (std::uint64_t at = 0; at + sizeof(Elf64_Sym) <= symbols.sh_size; at += sizeof(Elf64_Sym)) {
      Elf64_Sym sym;
      std::memcpy(&sym, bytes.data() + symbols.sh_offset + at, sizeof sym);
      if (sym.st_name >= names.sh_size) continue;
      const char* name = bytes.data() + names.sh_offset + sym.st_name;
      const std::size_t room = static_cast<std::size_t>(names.sh_size - sym.st_name);
      if (strnlen(name, room) == room || std::strcmp(name, "radchain_plugin_abi_version") != 0) continue;
      // (At least four bytes, not exactly: clang's AddressSanitizer pads an instrumented global with its redzone and
      // the symbol's size counts the padding; the number is still the first four bytes.)
      if (sym.st_shndx == SHN_UNDEF || sym.st_shndx >= eh.e_shnum || sym.st_size < sizeof(std::uint32_t))
        return std::nullopt;
      const Elf64_Shdr data = section(sym.st_shndx);
      if (data.sh_type == SHT_NOBITS) return 0u;
      if (sym.st_value < data.sh_addr) return std::nullopt;
      const std::uint64_t offset = data.sh_offset + (sym.st_value - data.sh_addr);
      if (!fits(offset, sizeof(std::uint32_t))) return std::nullopt;
      std::uint32_t abi = 0;
      std::memcpy(&abi, bytes.data() + offset, sizeof abi);
      return abi;
    }
    return 0u;  // a dynamic symbol table without the symbol
  }
  return std::nullopt;
}
std::string with_article(const std::string& noun) {
  return (noun.empty() || std::string("aeiou").find(noun.front()) == std::string::npos ? "a " : "an ") + noun;
}
}  // namespace

struct PluginHost::Impl {
  std::mutex mutex;  // sensor files load in parallel (catalogue)
  std::deque<boost::dll::shared_library> libraries;  // never unloaded
  std::map<std::string, const PluginInfo*> by_path;
  std::map<std::string, const PluginInfo*, std::less<>> by_name;  // first loaded under a name
  std::set<std::string> shadow_warnings;
  std::optional<std::vector<PluginFile>> discovered;  // the scan of the current search path
  std::deque<PluginInfo> added;                       // add(): never freed
  std::map<std::string, const PluginInfo*, std::less<>> added_by_name;
};

PluginHost& PluginHost::instance() {
  static PluginHost* host = new PluginHost();  // intentionally never destroyed: libraries outlive every object
  return *host;
}

PluginHost::PluginHost() : impl_(new Impl) { configure({}); }

void PluginHost::configure(const std::vector<std::string>& explicit_dirs) {
  std::lock_guard lock(impl_->mutex);
  impl_->discovered.reset();  // a new search path: scan again at the next look-up
  search_path_.clear();
  auto add = [&](const std::string& dir) {
    if (!dir.empty() && std::find(search_path_.begin(), search_path_.end(), dir) == search_path_.end())
      search_path_.push_back(dir);
  };
  for (const auto& d : explicit_dirs) {
    std::stringstream parts(d);
    std::string part;
    while (std::getline(parts, part, ':')) add(part);
  }
  if (const char* env = std::getenv("RADCHAIN_PLUGIN_PATH")) {
    std::stringstream parts(env);
    std::string part;
    while (std::getline(parts, part, ':')) add(part);
  }
  std::error_code ec;
  const fs::path exe_dir = boost::dll::program_location(ec).parent_path();
  if (!ec) {
    add((exe_dir / "plugins").string());                           // build tree
    add((exe_dir / ".." / "lib" / "radchain" / "plugins").lexically_normal().string());
  }
#ifdef RADCHAIN_INSTALL_PLUGIN_DIR
  add(RADCHAIN_INSTALL_PLUGIN_DIR);
#endif
}

std::vector<PluginFile> PluginHost::discover() const {
  std::lock_guard lock(impl_->mutex);
  return discovered();
}

const std::vector<PluginFile>& PluginHost::discovered() const {
  if (impl_->discovered) return *impl_->discovered;
  std::vector<PluginFile> found;
  std::map<std::string, std::string> first_path;  // name -> path
  for (const auto& dir : search_path_) {
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) continue;
    for (const auto& kind_dir : fs::directory_iterator(dir, ec)) {
      const auto kind = kind_from_name(kind_dir.path().filename().string());
      if (!kind || !kind_dir.is_directory()) continue;
      std::vector<fs::path> files;
      for (const auto& file : fs::directory_iterator(kind_dir.path(), ec))
        if (file.is_regular_file() && file.path().extension() == ".so") files.push_back(file.path());
      std::sort(files.begin(), files.end());
      for (const auto& file : files) {
        const std::string name = file.stem().string();
        auto [it, inserted] = first_path.emplace(name, file.string());
        if (inserted) {
          found.push_back(PluginFile{name, *kind, file.string()});
        } else if (it->second != file.string() && !fs::equivalent(it->second, file, ec) &&  // one folder named twice
                   impl_->shadow_warnings.insert(file.string()).second) {
          std::cerr << fmt::format("radchain: plugin \"{}\" at {} is shadowed by {} (first in the search path wins)\n",
                                   name, file.string(), it->second);
        }
      }
    }
  }
  std::sort(found.begin(), found.end(), [](const PluginFile& a, const PluginFile& b) {
    return std::make_pair(static_cast<int>(a.kind), a.name) < std::make_pair(static_cast<int>(b.kind), b.name);
  });
  return impl_->discovered.emplace(std::move(found));
}

const PluginInfo* PluginHost::loaded(std::string_view name) const {
  std::lock_guard lock(impl_->mutex);
  auto it = impl_->by_name.find(name);
  return it == impl_->by_name.end() ? nullptr : it->second;
}

const PluginInfo& PluginHost::load_file(const std::string& path) {
  std::lock_guard lock(impl_->mutex);
  return load_file_locked(path);
}

const PluginInfo& PluginHost::load_file_locked(const std::string& path) {
  if (auto it = impl_->by_path.find(path); it != impl_->by_path.end()) return *it->second;
  auto fail = [&](const std::string& problem) { return InputError(SourceLocation{path, 0, 0}, "plugin library", "", problem); };

  // First from the file, so that a library of another ABI (or no plugin at all) never runs its constructors.
  if (const auto abi = abi_in_file(path)) {
    if (*abi == 0)
      throw fail("not a radchain plugin: it exports no radchain_plugin_abi_version (declare it with RADCHAIN_PLUGIN)");
    if (*abi != plugin_abi_version)
      throw fail(fmt::format("built for plugin ABI {}, this radchain {} has ABI {}: rebuild the plugin against it", *abi,
                             framework_version, plugin_abi_version));
  }
  boost::dll::shared_library library;
  std::error_code ec;
  library.load(fs::path(path), boost::dll::load_mode::rtld_now | boost::dll::load_mode::rtld_local, ec);
  if (ec) {
    // Boost keeps only an error code; ask the dynamic loader for its reason (error path only).
    std::string reason = "not a loadable shared library";
    if (void* handle = ::dlopen(path.c_str(), RTLD_NOW | RTLD_LOCAL)) {
      ::dlclose(handle);
    } else if (const char* why = ::dlerror()) {
      reason = why;
    }
    throw fail("cannot be loaded: " + reason);
  }
  // The ABI number is read before anything in the library is called.
  if (!library.has("radchain_plugin_abi_version"))
    throw fail("not a radchain plugin: it exports no radchain_plugin_abi_version (declare it with RADCHAIN_PLUGIN)");
  const std::uint32_t abi = library.get<const std::uint32_t>("radchain_plugin_abi_version");
  if (abi != plugin_abi_version)
    throw fail(fmt::format("built for plugin ABI {}, this radchain {} has ABI {}: rebuild the plugin against it", abi,
                           framework_version, plugin_abi_version));
  if (!library.has("radchain_plugin_info"))
    throw fail("no entry symbol radchain_plugin_info (declare it with RADCHAIN_PLUGIN at the bottom of the plugin)");
  const PluginInfo& info = library.get_alias<const PluginInfo&()>("radchain_plugin_info")();
  if (info.abi_version != plugin_abi_version)
    throw fail(fmt::format("its PluginInfo says ABI {}, this radchain has ABI {}", info.abi_version, plugin_abi_version));
  const std::string stem = fs::path(path).stem().string();
  if (stem != info.name)
    throw fail(fmt::format("declares the name \"{}\" but the file is named \"{}\": the two must be one string", info.name, stem));
  const auto dir_kind = kind_from_name(fs::path(path).parent_path().filename().string());
  if (dir_kind && *dir_kind != info.kind)
    throw fail(fmt::format("is a {} plugin but lies in a {}/ folder", to_string(info.kind), kind_directory(*dir_kind)));
  impl_->libraries.push_back(std::move(library));
  impl_->by_path.emplace(path, &info);
  impl_->by_name.emplace(info.name, &info);
  return info;
}

const PluginInfo& PluginHost::add(PluginInfo info) {
  std::lock_guard lock(impl_->mutex);
  const PluginInfo& added = impl_->added.emplace_back(std::move(info));
  impl_->added_by_name[added.name] = &added;
  impl_->by_name[added.name] = &added;
  return added;
}

const PluginInfo& PluginHost::load(Kind kind, const std::string& name) {
  std::lock_guard lock(impl_->mutex);
  if (auto it = impl_->added_by_name.find(name); it != impl_->added_by_name.end() && it->second->kind == kind)
    return *it->second;
  std::vector<std::string> available;
  std::optional<Kind> other_kind;  // the name exists, but for another section
  for (const auto& file : discovered()) {
    if (file.kind != kind) {
      if (file.name == name) other_kind = file.kind;
      continue;
    }
    if (file.name == name) return load_file_locked(file.path);
    available.push_back(file.name);
  }
  const std::string hint = other_kind ? fmt::format(" (\"{}\" is {} plugin)", name, with_article(to_string(*other_kind)))
                                      : did_you_mean(name, available);
  // The subject names the plugin; a caller that already shows the name uses problem() alone.
  throw InputError({}, "", fmt::format("plugin \"{}\"", name),
                   fmt::format("unknown {} plugin{}; available: {} (search path: {})", to_string(kind), hint,
                               available.empty() ? "none" : join(available), join(search_path_, ":")));
}

}  // namespace radchain
