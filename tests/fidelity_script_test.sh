#!/usr/bin/env bash
# ctest Scripts.Fidelity: scripts/fidelity.sh end to end at the smallest size (one case, four
# variants: two models with multiple scattering on and off, 16 samples per pixel, 48 x 32) with the
# built wisp: the table has a row per variant and a column per varied setting, fidelity.json one
# case with its measurements (kajiya's the same with multiple scattering on or off), the pictures
# are packed; and its bad input (a
# missing binary or data, a bad number, a refused setting, an earlier run) exits 2 with a message
# naming it and writes nothing.
# Usage: tests/fidelity_script_test.sh PATH/TO/wisp
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
wisp="${1:?usage: fidelity_script_test.sh PATH/TO/wisp}"
tmp="$(mktemp -d)"
trap 'rm -rf "$tmp"' EXIT
failures=0
fail() {
  echo "FAILED: $*" >&2
  failures=$((failures + 1))
}

# refused CASE_NAME EXPECTED_TEXT ARGS...: exit 2, the text on stderr, OUT_DIR not made.
refused() {
  local name="$1" text="$2"
  shift 2
  local status=0
  "$@" >"$tmp/$name.out" 2>"$tmp/$name.err" || status=$?
  [ $status = 2 ] || fail "$name: exit $status, not 2 ($(cat "$tmp/$name.err"))"
  grep -qF -- "$text" "$tmp/$name.err" || fail "$name: stderr lacks '$text': $(cat "$tmp/$name.err")"
  [ ! -e "$tmp/$name" ] || fail "$name: $tmp/$name was written"
}
small=(--grooms default --lights front --colours brown --guides 20 --set strands_per_guide=2 --frames 2
  --width 48 --height 32 --spp 16)
WISP="$tmp/no-such-wisp" refused missing-binary "the wisp binary $tmp/no-such-wisp is missing" \
  "$root/scripts/fidelity.sh" "$tmp/missing-binary" "${small[@]}"
WISP="$wisp" refused missing-data "Sintel's groom needs $tmp/nowhere/sintel/sintel.obj" \
  "$root/scripts/fidelity.sh" "$tmp/missing-data" "$tmp/nowhere" --grooms sintel
WISP="$wisp" refused bad-spp "--spp: '0' is not a whole number of at least 1" \
  "$root/scripts/fidelity.sh" "$tmp/bad-spp" --spp 0
WISP="$wisp" refused bad-light "--lights: 'side' is not one of: front back" \
  "$root/scripts/fidelity.sh" "$tmp/bad-light" --lights front,side
WISP="$wisp" refused bad-setting "--set shading=phong" \
  "$root/scripts/fidelity.sh" "$tmp/bad-setting" "${small[@]}" --vary shading=karis,phong
WISP="$wisp" refused bad-on-off "--set multiple_scattering=sometimes" \
  "$root/scripts/fidelity.sh" "$tmp/bad-on-off" "${small[@]}" --vary multiple_scattering=on,sometimes

out="$tmp/run"
start=$SECONDS
status=0
WISP="$wisp" "$root/scripts/fidelity.sh" "$out" "${small[@]}" --vary shading=karis,kajiya \
  --vary multiple_scattering=on,off --no-terms 2>"$tmp/run.err" ||
  status=$?
[ $status = 0 ] || { cat "$tmp/run.err" >&2; fail "the run exited $status"; }
echo "fidelity.sh took $((SECONDS - start)) s" >&2
# The first table: its header, then a row per variant (the closest in bold).
table="$(awk '/^\| case \| shading \| multiple_scattering \| RMSE/ {on = 1} on && /^$/ {exit} on' "$out/fidelity.md")"
rows="$(echo "$table" | tail -n +3 | sed 's/\*\*//g' | cut -d'|' -f2,3,4 | tr -d ' ')"
expected="$(printf 'default-front-brown|karis|%s\n' on off; printf 'default-front-brown|kajiya|%s\n' on off)"
[ "$rows" = "$expected" ] ||
  fail "fidelity.md's table has these rows (case|shading|multiple_scattering), not karis and kajiya, on and off: $rows"
grep -qF '| case | shading=karis multiple_scattering=on | shading=karis multiple_scattering=off |' "$out/fidelity.md" ||
  fail "fidelity.md's first table does not name the variants' columns"
grep -q '^| \*\*default-front-brown\*\* | ' <<<"$table" || fail "fidelity.md marks no closest variant"
python3 - "$out/fidelity.json" <<'EOF' || fail "fidelity.json is not as expected"
import json, sys
r = json.load(open(sys.argv[1]))
assert [c["case"] for c in r["cases"]] == ["default-front-brown"], r["cases"]
c = r["cases"][0]
assert [v["settings"] for v in c["variants"]] == [
    {"shading": m, "multiple_scattering": s} for m in ("karis", "kajiya") for s in ("on", "off")], c["variants"]
for v in c["variants"]:
    assert 0 < v["frame"]["rmse"] < 1 and 0 < v["hair"]["rmse"] < 1 and v["hair"]["pixels"] > 0, v
karis_on, karis_off, kajiya_on, kajiya_off = c["variants"]
assert karis_on["hair"] != karis_off["hair"], "multiple_scattering=off changed nothing in karis"
assert kajiya_on["hair"] == kajiya_off["hair"], "kajiya has no multiple scattering to turn off"
assert c["reference"]["noise_levels"] > 0 and 0 < c["reference"]["second"]["frame"]["rmse"] < 1, c["reference"]
assert r["packed"]["files"] > 0 and not r["packed"]["left_out"], r["packed"]
EOF
# The listing whole first: grep -q stops at the first match (the reference is packed first), and
# under pipefail the tar it leaves writing into a closed pipe would fail the check.
packed="$(tar -tf "$out/fidelity-images.tar")"
grep -qx 'default-front-brown/reference.png' <<<"$packed" ||
  fail "fidelity-images.tar lacks the reference"
if command -v ffmpeg >/dev/null; then
  [ -s "$out/fidelity-default.png" ] && [ -s "$out/fidelity-default-all.png" ] || fail "no sheets"
fi
status=0
WISP="$wisp" "$root/scripts/fidelity.sh" "$out" "${small[@]}" >"$tmp/again.out" 2>"$tmp/again.err" || status=$?
[ $status = 2 ] && grep -qF -- "--overwrite replaces it" "$tmp/again.err" ||
  fail "a second run into the same folder: exit $status, $(cat "$tmp/again.err")"
[ $failures = 0 ] || exit 1
echo "fidelity.sh: all checks passed"
