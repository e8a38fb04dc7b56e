#!/usr/bin/env bash
# Lets a fresh clone reuse the build outputs of the last complete CI run at the same path.
#
#   scripts/source-mtimes.sh restore MANIFEST   before building
#   scripts/source-mtimes.sh record MANIFEST    after a complete, successful run
#
# cargo decides whether a workspace crate is fresh by comparing its source files' mtimes
# with its last build, and a clone stamps every file with the time of the clone, so each
# fresh clone would rebuild every workspace crate (and the fuzz and Python crates) although
# the cache outside the clone holds them already. `record` writes each tracked file's git
# blob id and mtime; `restore` gives a file its recorded mtime back only where its blob id
# (its content) is the recorded one, so a changed file keeps the clone's time and what
# reads it is rebuilt. Content decides, never time alone.
#
# The manifest describes the cache only after a run that built everything from this tree:
# `restore` removes it before anything is built (a run that stops half-way leaves none, and
# the next run rebuilds what it needs), and `record` refuses a tree with changes to tracked
# files. A path with whitespace, or no manifest, leaves every mtime as it is.
set -euo pipefail
cd "$(dirname "$0")/.."

usage() {
  echo "usage: scripts/source-mtimes.sh restore|record MANIFEST" >&2
  exit 2
}
[ $# -eq 2 ] || usage
manifest=$2
log() { printf '[mtimes] %s\n' "$*" >&2; }

if git ls-files | grep -q '[[:space:]]'; then
  log "a tracked path has whitespace; mtimes left as they are"
  exit 0
fi

case $1 in
  record)
    if [ -n "$(git status --porcelain --untracked-files=no)" ]; then
      log "tracked files differ from the commit; no manifest written"
      rm -f "$manifest"
      exit 0
    fi
    mkdir -p "$(dirname "$manifest")"
    # blob id, path (from the index, which matches the tree: checked above) and mtime
    git ls-files -s | awk '{ split($0, t, "\t"); print $2 "\t" t[2] }' >"$manifest.blobs"
    cut -f2 "$manifest.blobs" | xargs stat -c '%.9Y' >"$manifest.times"
    paste "$manifest.blobs" "$manifest.times" >"$manifest.new"
    rm -f "$manifest.blobs" "$manifest.times"
    mv "$manifest.new" "$manifest"
    log "recorded $(wc -l <"$manifest") files in $manifest"
    ;;
  restore)
    if [ ! -f "$manifest" ]; then
      log "no manifest at $manifest: every crate of this clone builds afresh"
      exit 0
    fi
    using=$manifest.using
    mv "$manifest" "$using"
    # recorded "blob path mtime" against the clone's "mode blob stage<TAB>path":
    # "mtime<TAB>path" for each file whose content is the recorded one, then for each
    # directory all of whose tracked files are (cargo may scan a watched directory's own
    # mtime too), the latest of theirs
    matched=$(git ls-files -s | awk -F'\t' '
      NR == FNR { blob[$2] = $1; time[$2] = $3; next }
      {
        split($1, m, " "); same = ($2 in blob) && blob[$2] == m[2]
        if (same) print time[$2] "\t" $2
        d = $2
        while (sub(/\/[^\/]*$/, "", d)) {
          if (!same) dirty[d] = 1
          else if (!(d in latest) || time[$2] > latest[d]) latest[d] = time[$2]
        }
      }
      END { for (d in latest) if (!(d in dirty)) print latest[d] "\t" d }
    ' "$using" -)
    rm -f "$using"
    n=0
    while IFS=$'\t' read -r t path; do
      [ -n "$path" ] || continue
      touch -m -d "@$t" -- "$path"
      n=$((n + 1))
    done <<<"$matched"
    log "$n files and directories as the last complete run built them (of $(git ls-files | wc -l) files); the rest rebuild"
    ;;
  *) usage ;;
esac
