# Sourced by tools/clang_tidy.sh and tools/clang_format_check.sh: change_base TOOL prints the commit "the change" is
# measured from (TILEVK_TIDY_BASE if set; on a branch that main does not contain, its merge base with main; on main,
# the last commit's first parent), or "root" for a root commit. TOOL names the caller in its error messages.
change_base() {
    if [[ -n "${TILEVK_TIDY_BASE:-}" ]]; then
        git rev-parse --verify -q "$TILEVK_TIDY_BASE^{commit}" || return 1
        return 0
    fi
    local main_ref
    for main_ref in main origin/main; do
        if git rev-parse --verify -q "$main_ref^{commit}" >/dev/null; then
            local mb
            mb=$(git merge-base HEAD "$main_ref") || return 1
            if [[ "$mb" != "$(git rev-parse HEAD)" ]]; then
                echo "$mb"
                return 0
            fi
            break
        fi
    done
    if git rev-parse --verify -q HEAD^ >/dev/null; then
        git rev-parse HEAD^
        return 0
    fi
    if [[ "$(git rev-parse --is-shallow-repository)" == "true" ]]; then
        echo "$1: a shallow clone has no parent commit to compare with; set TILEVK_TIDY_BASE" >&2
        return 1
    fi
    echo "root"
}
