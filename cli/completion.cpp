#include "cli/completion.hpp"

#include <string_view>

namespace dem::cli {
namespace {

// How an option's value is completed: "dir", "file", "words:a,b,c" or "none".
std::string value_kind(std::string_view value) {
  if (value == "DIR") return "dir";
  if (value.find('|') != std::string_view::npos) {
    std::string words = "words:";
    for (const char c : value) words += c == '|' ? ',' : c;
    return words;
  }
  const auto ends_with = [&](std::string_view end) {
    return value.size() >= end.size() && value.substr(value.size() - end.size()) == end;
  };
  if (value == "FILE" || value == "MESH" || ends_with(".json") || ends_with(".svg")) return "file";
  return "none";
}

// A job or study id is not a file.
bool positional_is_a_file(const Verb& verb) {
  const std::string_view first = verb.first;
  return !first.empty() && first.find(" id") == std::string_view::npos;
}

}  // namespace

std::string bash_completion(const std::vector<const Verb*>& verbs) {
  std::string names, per_verb;
  for (const Verb* verb : verbs) {
    names += std::string(verb->name) + " ";
    std::string options = "--help --version", values;
    std::vector<VerbOption> all = verb->options;
    if (verb->client) all.insert(all.end(), client_options().begin(), client_options().end());
    for (const VerbOption& o : all) {
      options += std::string(" ") + o.name;
      if (o.value != nullptr) values += std::string(" ") + o.name + "=" + value_kind(o.value);
    }
    per_verb += std::string("    ") + verb->name + ") options=\"" + options + "\"; values=\"" +
                (values.empty() ? values : values.substr(1)) +
                "\"; files=" + (positional_is_a_file(*verb) ? "yes" : "no") + " ;;\n";
  }
  return "# bash completion for dem: source <(dem completion bash), or install it as\n"
         "# /usr/share/bash-completion/completions/dem (cmake --install does)\n"
         "_dem() {\n"
         "  local cur=\"${COMP_WORDS[COMP_CWORD]}\" prev=\"${COMP_WORDS[COMP_CWORD-1]}\"\n"
         "  COMPREPLY=()\n"
         "  # --opt=VALUE: bash splits it at '=' into --opt, = and VALUE\n"
         "  if [ \"$cur\" = = ]; then\n"
         "    cur=\"\"\n"
         "  elif [ \"$prev\" = = ] && [ \"$COMP_CWORD\" -ge 2 ]; then\n"
         "    prev=\"${COMP_WORDS[COMP_CWORD-2]}\"\n"
         "  fi\n"
         "  if [ \"$COMP_CWORD\" -eq 1 ]; then\n"
         "    COMPREPLY=($(compgen -W \"" +
         names +
         "completion help --help --version\" -- \"$cur\"))\n"
         "    return\n"
         "  fi\n"
         "  local options=\"\" values=\"\" files=no\n"
         "  case \"${COMP_WORDS[1]}\" in\n" +
         per_verb +
         "    completion) [ \"$COMP_CWORD\" -eq 2 ] && COMPREPLY=($(compgen -W bash -- \"$cur\")); return ;;\n"
         "    *) return ;;\n"
         "  esac\n"
         "  local pair kind\n"
         "  for pair in $values; do\n"
         "    [ \"${pair%%=*}\" = \"$prev\" ] || continue\n"
         "    kind=\"${pair#*=}\"\n"
         "    case \"$kind\" in\n"
         "      dir) mapfile -t COMPREPLY < <(compgen -d -- \"$cur\") ;;\n"
         "      file) mapfile -t COMPREPLY < <(compgen -f -- \"$cur\") ;;\n"
         "      words:*) kind=\"${kind#words:}\"; COMPREPLY=($(compgen -W \"${kind//,/ }\" -- \"$cur\")) ;;\n"
         "    esac\n"
         "    return\n"
         "  done\n"
         "  if [[ \"$cur\" == -* ]]; then\n"
         "    COMPREPLY=($(compgen -W \"$options\" -- \"$cur\"))\n"
         "  elif [ \"$files\" = yes ]; then\n"
         "    mapfile -t COMPREPLY < <(compgen -f -- \"$cur\")\n"
         "  fi\n"
         "}\n"
         "complete -o filenames -o bashdefault -F _dem dem\n";
}

}  // namespace dem::cli
