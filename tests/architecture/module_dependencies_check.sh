#!/usr/bin/env bash
# The module table of ARCHITECTURE.md is the rule: every `#include "feedplan/<module>/…"` in a module's
# headers and sources must name the module itself or one listed in its "may include" column. Fails with
# every include that breaks the rule (file:line, the module it includes, what the row allows).
#
# Usage: module_dependencies_check.sh SOURCE_DIR
set -euo pipefail
src=$1
table="$src/ARCHITECTURE.md"
[[ -f $table ]] || { echo "$table is missing"; exit 1; }

declare -A allowed
while IFS='|' read -r _ module deps _; do
  module=$(echo "$module" | tr -d ' ')
  deps=$(echo "$deps" | tr -d ' ')
  [[ -z $module || $module == module || $module =~ ^-+$ ]] && continue
  allowed[$module]=$deps
done < <(sed -n '/^| module | may include |/,/^$/p' "$table")
((${#allowed[@]} > 0)) || { echo "no module table found in $table"; exit 1; }

bad=0
for module in "${!allowed[@]}"; do
  deps=${allowed[$module]}
  [[ $deps == everymodule ]] && continue
  [[ -d $src/$module ]] || { echo "ARCHITECTURE.md lists $module, but there is no folder $module/"; bad=1; continue; }
  while IFS=: read -r file line included; do
    [[ $included == "$module" ]] && continue
    if [[ ",$deps," != *",$included,"* ]]; then
      echo "${file#"$src"/}:$line includes feedplan/$included/, but $module may include only: ${deps//,/, }"
      bad=1
    fi
  done < <(grep -rnoE '#include "feedplan/[a-z_]+/' "$src/$module" --include='*.hpp' --include='*.cpp' |
           sed -E 's|#include "feedplan/([a-z_]+)/|\1|')
done
for folder in "$src"/*/CMakeLists.txt; do
  module=$(basename "$(dirname "$folder")")
  [[ $module == tests || $module == bench ]] && continue
  [[ -n ${allowed[$module]+x} ]] || { echo "module $module/ is not in the table of ARCHITECTURE.md"; bad=1; }
done
((bad == 0)) && echo "every include follows the module table of ARCHITECTURE.md (${#allowed[@]} modules)"
exit "$bad"
