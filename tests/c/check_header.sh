#!/bin/sh
# The public headers compile without a warning under -Wpedantic -Werror as
# C11, C99 and (when a C++ compiler is found) C++11: renderers include them
# from C++.  usage: check_header.sh CC INCLUDE_DIR
set -eu
cc="$1" inc="$2"
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT
cat > "$tmp/use.c" <<'SRC'
#include <mcstat.h>
#include <mcstat/embedded.h>
#include <mcstat_check.h>
int use(mcstat_result *r);
int use(mcstat_result *r)
{
    mcstat_ks_options o = MCSTAT_KS_OPTIONS_INIT;
    (void)mcstat_ks_options_init(&o);
    return r->ks_weight + (int)r->ks_n_sim + (int)r->reserved[1] + r->reserved_i[0] + o.threads +
           (r->decision == MCSTAT_DECISION_LESS);
}
SRC
for std in c11 c99; do
    "$cc" -std=$std -Wall -Wextra -Wpedantic -Werror -I "$inc" -c "$tmp/use.c" -o "$tmp/use.o" \
        || { echo "mcstat.h: warnings as $std"; exit 1; }
done
# without the experimental sections (MCSTAT_NO_EXPERIMENTAL) the rest still
# compiles, and the experimental names are gone
"$cc" -std=c11 -Wall -Wextra -Wpedantic -Werror -DMCSTAT_NO_EXPERIMENTAL -I "$inc" -c "$tmp/use.c" -o "$tmp/use.o" \
    || { echo "mcstat.h: does not compile with MCSTAT_NO_EXPERIMENTAL"; exit 1; }
printf '#include <mcstat.h>\nint exp_use(mcstat_gof_options *o);\n' > "$tmp/exp.c"
"$cc" -std=c11 -I "$inc" -c "$tmp/exp.c" -o "$tmp/exp.o" || { echo "mcstat.h: experimental names missing"; exit 1; }
if "$cc" -std=c11 -DMCSTAT_NO_EXPERIMENTAL -I "$inc" -c "$tmp/exp.c" -o "$tmp/exp.o" 2> /dev/null; then
    echo "mcstat.h: MCSTAT_NO_EXPERIMENTAL leaves the experimental names in"; exit 1
fi
# the stable families stay with MCSTAT_NO_EXPERIMENTAL: the renderer checks
# and the sequential tests
printf '#include <mcstat.h>\nint st(mcstat_check_model *m, mcstat_seq *s);\n' > "$tmp/stable.c"
"$cc" -std=c11 -Wall -Werror -DMCSTAT_NO_EXPERIMENTAL -I "$inc" -c "$tmp/stable.c" -o "$tmp/stable.o" \
    || { echo "mcstat.h: MCSTAT_NO_EXPERIMENTAL leaves out a stable family"; exit 1; }
# an experimental call warns, naming the opt-in, unless MCSTAT_EXPERIMENTAL
# is defined (or deprecation warnings are off)
cat > "$tmp/optin.c" <<'SRC'
#include <mcstat.h>
double p(void);
double p(void)
{
    mcstat_result r;
    return mcstat_binom_test(3, 10, 0.5, MCSTAT_TWO_SIDED, 0.05, &r) ? -1.0 : r.p_value;
}
SRC
if "$cc" -std=c11 -Werror -I "$inc" -c "$tmp/optin.c" -o "$tmp/optin.o" 2> "$tmp/optin.err"; then
    echo "mcstat.h: an experimental call without MCSTAT_EXPERIMENTAL does not warn"; exit 1
fi
grep -q "MCSTAT_EXPERIMENTAL" "$tmp/optin.err" \
    || { echo "mcstat.h: the experimental warning does not name MCSTAT_EXPERIMENTAL"; cat "$tmp/optin.err"; exit 1; }
for def in MCSTAT_EXPERIMENTAL MCSTAT_DISABLE_DEPRECATE_WARNINGS; do
    "$cc" -std=c11 -Wall -Wextra -Wpedantic -Werror -D$def -I "$inc" -c "$tmp/optin.c" -o "$tmp/optin.o" \
        || { echo "mcstat.h: an experimental call warns with $def"; exit 1; }
done
# a renamed constant warns with its new name where the compiler can say so
printf '#include <mcstat.h>\nint old_name(void);\nint old_name(void) { return MCSTAT_DOMAIN_SPHERE; }\n' > "$tmp/old.c"
if "$cc" -std=c11 -Werror -I "$inc" -c "$tmp/old.c" -o "$tmp/old.o" 2> "$tmp/old.err"; then
    case $("$cc" --version 2>&1) in
        *gcc*|*GCC*|*clang*) echo "mcstat.h: MCSTAT_DOMAIN_SPHERE does not warn"; exit 1 ;;
    esac
else
    grep -q MCSTAT_CHECK_DOMAIN_SPHERE "$tmp/old.err" \
        || { echo "mcstat.h: the warning on MCSTAT_DOMAIN_SPHERE does not name its replacement"; exit 1; }
fi
# each family compiles alone, and with the old name of mcstat/embedded.h
for h in "$inc"/mcstat/*.h "$inc/mcstat_check.h"; do
    name=${h#"$inc"/}
    printf '#define MCSTAT_EXPERIMENTAL\n#define MCSTAT_CHECKS 1\n#include <%s>\nint family_alone;\n' "$name" > "$tmp/alone.c"
    "$cc" -std=c11 -Wall -Wextra -Wpedantic -Werror -I "$inc" -c "$tmp/alone.c" -o "$tmp/alone.o" \
        || { echo "$name: does not compile alone"; exit 1; }
done
# an ignored status warns where the language has [[nodiscard]] (C++17 here);
# a (void) cast says it was meant
cat > "$tmp/status.cpp" <<'SRC'
#include <mcstat.h>
double ignored(const double *x, mcstat_result *r);
double ignored(const double *x, mcstat_result *r)
{
    IGNORE mcstat_t_test_1(x, 10, 0.0, MCSTAT_TWO_SIDED, 0.05, r);
    return r->p_value;
}
SRC
for cxx in c++ g++ clang++; do
    if command -v "$cxx" > /dev/null 2>&1; then
        if "$cxx" -std=c++17 -Werror=unused-result -DIGNORE= -I "$inc" -c "$tmp/status.cpp" -o "$tmp/s.o" 2> /dev/null; then
            echo "mcstat.h: an ignored status does not warn in C++17 ($cxx)"; exit 1
        fi
        "$cxx" -std=c++17 -Wall -Wextra -Werror -D'IGNORE=(void)' -I "$inc" -c "$tmp/status.cpp" -o "$tmp/s.o" \
            || { echo "mcstat.h: a (void) cast does not silence an ignored status in C++17 ($cxx)"; exit 1; }
        cp "$tmp/use.c" "$tmp/use.cpp"
        "$cxx" -std=c++11 -Wall -Wextra -Wpedantic -Werror -I "$inc" -c "$tmp/use.cpp" -o "$tmp/use.o" \
            || { echo "mcstat.h: warnings as C++11 ($cxx)"; exit 1; }
        echo "mcstat.h: clean as C11, C99 and C++11 ($cxx)"
        exit 0
    fi
done
echo "mcstat.h: clean as C11 and C99 (no C++ compiler found)"
