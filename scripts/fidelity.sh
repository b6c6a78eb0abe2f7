#!/usr/bin/env bash
# The fidelity table: how far each real-time frame is from the path-traced reference of
# the same frame. For each case (groom x key light x hair colour) it renders the reference once
# (`wisp render --reference`), the frame without hair (compare's mask) and every real-time variant
# (the product of the --vary lists: by default shading=karis,kajiya,lut x dom_layers=4,0), measures
# each with `wisp compare --json`, and writes into OUT_DIR:
#   fidelity.md          the table (RMSE, relMSE, SSIM over the frame and over the hair) and summaries
#   fidelity.json        every measurement, the command, the device, the references' noise
#   fidelity-GROOM.png   per case: reference | best real-time | its error | worst | its error
#   fidelity-GROOM-all.png  per case: the reference and every variant, smaller
#   fidelity-images.tar  the pictures themselves (references first), up to --pack-mb
#   fidelity.log         what ran
# and the work files (every picture, log and measurement) under OUT_DIR/work/.
# Each picture is its own `wisp render` (the same command gives the same picture), so the run is
# deterministic for a device; --jobs runs several at once.
#
# Usage: scripts/fidelity.sh OUT_DIR [DATA_DIR] [OPTIONS]
#   DATA_DIR               holds sintel/sintel.obj and sintel/sintel_hair_11400x16.tfx (default:
#                          $WISP_SHARED_DATA, else ../shared/data beside the checkout)
#   --spp N                the references' samples per pixel (default 256)
#   --width W --height H   picture size (default 480 x 270)
#   --frames N             simulated frames before each picture (default 30)
#   --grooms LIST          default,sintel (default both; sintel needs DATA_DIR)
#   --lights LIST          front,back: the key light at azimuth 40, elevation 35 (the default) or
#                          behind the head, azimuth 160, elevation 20 (default both)
#   --colours LIST         brown,blonde (hair_preset; default both)
#   --guides N             the default groom's guides (default its own, 2200)
#   --vary NAME=V1,V2,...  a setting the real-time variants take each value of (repeatable; given
#                          once, it replaces the default shading=karis,kajiya,lut and dom_layers=4,0)
#   --set NAME=VALUE       a setting for every picture, the reference's too (repeatable)
#   --no-terms             skip the light terms (the first variant and its reference with the key
#                          light alone, and without it: which light the error comes from)
#   --jobs N               renders at once (default 1)
#   --pack-mb M            fidelity-images.tar's size at most (default 15; what does not fit is
#                          listed in fidelity.md, and stays under work/)
#   --overwrite            replace an earlier run's results in OUT_DIR
#   --resume               complete an earlier run in OUT_DIR with the same options (one stopped
#                          midway): the pictures already there are kept, the rest drawn, all measured
# WISP=path/to/wisp chooses the binary (default build/wisp, or $WISP_BUILD_DIR/wisp). Needs bash,
# python3 (its standard library) and, for the sheets, ffmpeg or python3 with Pillow (without either
# the sheets are skipped, said in fidelity.md; FIDELITY_SHEETS=ffmpeg|pillow|none chooses). PYTHON=path
# chooses the python3; with numpy and Pillow it also takes the hair's error apart (noise, offset,
# luminance). Exit 2: bad input or a missing binary, data or tool.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"

die() {  # MESSAGE: bad input or environment
  echo "fidelity: $*" >&2
  exit 2
}

usage="usage: scripts/fidelity.sh OUT_DIR [DATA_DIR] [--spp N] [--width W --height H] [--frames N] [--grooms default,sintel] [--lights front,back] [--colours brown,blonde] [--guides N] [--vary NAME=V1,V2,...] [--set NAME=VALUE] [--no-terms] [--jobs N] [--pack-mb M] [--overwrite | --resume]"
out=""
data=""
spp=256
width=480
height=270
frames=30
grooms="default,sintel"
lights="front,back"
colours="brown,blonde"
guides=""
varies=()
sets=()
terms=1
jobs=1
pack_mb=15
overwrite=0
resume=0
command_line="scripts/fidelity.sh $*"

positive() {  # OPTION VALUE [MIN]: a whole number of at least MIN (default 1)
  [[ "$2" =~ ^[0-9]+$ ]] && [ "${#2}" -le 9 ] && [ "$2" -ge "${3:-1}" ] ||
    die "$1: '$2' is not a whole number of at least ${3:-1}"
}
needvalue() {  # OPTION ARGC
  [ "$2" -ge 2 ] || die "$1 needs a value ($usage)"
}
while [ $# -gt 0 ]; do
  case "$1" in
  --spp) needvalue "$1" $#; positive "$1" "$2"; spp="$2"; shift 2 ;;
  --width) needvalue "$1" $#; positive "$1" "$2" 16; width="$2"; shift 2 ;;
  --height) needvalue "$1" $#; positive "$1" "$2" 16; height="$2"; shift 2 ;;
  --frames) needvalue "$1" $#; positive "$1" "$2" 0; frames="$2"; shift 2 ;;
  --grooms) needvalue "$1" $#; grooms="$2"; shift 2 ;;
  --lights) needvalue "$1" $#; lights="$2"; shift 2 ;;
  --colours) needvalue "$1" $#; colours="$2"; shift 2 ;;
  --guides) needvalue "$1" $#; positive "$1" "$2"; guides="$2"; shift 2 ;;
  --vary) needvalue "$1" $#; varies+=("$2"); shift 2 ;;
  --set) needvalue "$1" $#; sets+=("$2"); shift 2 ;;
  --no-terms) terms=0; shift ;;
  --jobs) needvalue "$1" $#; positive "$1" "$2"; jobs="$2"; shift 2 ;;
  --pack-mb) needvalue "$1" $#; positive "$1" "$2" 0; pack_mb="$2"; shift 2 ;;
  --overwrite) overwrite=1; shift ;;
  --resume) resume=1; shift ;;
  -h | --help) sed -n '2,/^set -euo/p' "$0" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
  -*) die "unknown option $1 ($usage)" ;;
  *)
    if [ -z "$out" ]; then out="$1"
    elif [ -z "$data" ]; then data="$1"
    else die "one OUT_DIR and one DATA_DIR at most, but '$1' too ($usage)"; fi
    shift ;;
  esac
done
[ -n "$out" ] || die "no OUT_DIR ($usage)"
if [ $overwrite = 1 ] && [ $resume = 1 ]; then die "--overwrite and --resume: one or the other"; fi
[ ${#varies[@]} -gt 0 ] || varies=("shading=karis,kajiya,lut" "dom_layers=4,0")
data="${data:-${WISP_SHARED_DATA:-$root/../shared/data}}"
wisp="${WISP:-${WISP_BUILD_DIR:-$root/build}/wisp}"

# ---- What is needed, checked before anything is written ---------------------------------------
[ -x "$wisp" ] && [ -f "$wisp" ] ||
  die "the wisp binary $wisp is missing or not executable (build it: scripts/build.sh wisp; or set WISP=path/to/wisp)"
python="${PYTHON:-python3}"
command -v "$python" >/dev/null || die "$python is missing (the table is assembled by its standard library; PYTHON=path chooses it)"
split_list() {  # ARRAY OPTION LIST ALLOWED...: the list's words into ARRAY, each one of ALLOWED
  local -n into="$1"
  local option="$2" list="$3"
  shift 3
  local word allowed ok
  into=()
  for word in ${list//,/ }; do
    ok=0
    for allowed in "$@"; do [ "$word" = "$allowed" ] && ok=1; done
    [ $ok = 1 ] || die "$option: '$word' is not one of: $*"
    into+=("$word")
  done
  [ ${#into[@]} -gt 0 ] || die "$option: the list is empty"
}
sheet_tool="${FIDELITY_SHEETS:-}"
case "$sheet_tool" in "" | ffmpeg | pillow | none) ;; *) die "FIDELITY_SHEETS=$sheet_tool: one of ffmpeg, pillow, none" ;; esac
if [ -z "$sheet_tool" ]; then
  sheet_tool=none
  if command -v ffmpeg >/dev/null; then
    sheet_tool=ffmpeg
  elif "$python" -c 'import PIL' 2>/dev/null; then
    sheet_tool=pillow
  fi
fi
groom_list=() light_list=() colour_list=()
split_list groom_list --grooms "$grooms" default sintel
split_list light_list --lights "$lights" front back
split_list colour_list --colours "$colours" brown blonde black auburn
sintel_head="$data/sintel/sintel.obj"
sintel_hair="$data/sintel/sintel_hair_11400x16.tfx"
for g in "${groom_list[@]}"; do
  if [ "$g" = sintel ]; then
    for f in "$sintel_head" "$sintel_hair"; do
      [ -f "$f" ] || die "Sintel's groom needs $f (DATA_DIR is $data; or --grooms default)"
    done
  fi
done
# Every --vary and --set is checked by wisp itself (`wisp settings` names them) on a tiny picture,
# so a typo stops the run before its first long render.
variant_names=()
variant_values=()
for v in "${varies[@]}"; do
  [[ "$v" =~ ^([a-z_0-9]+)=([^=]+)$ ]] || die "--vary: '$v' is not NAME=V1,V2,..."
  variant_names+=("${BASH_REMATCH[1]}")
  variant_values+=("${BASH_REMATCH[2]}")
done
set_args=()
for s in "${sets[@]}"; do
  [[ "$s" =~ ^[a-z_0-9]+=.+$ ]] || die "--set: '$s' is not NAME=VALUE"
  set_args+=(--set "$s")
done
if [ -e "$out" ] && [ -n "$(ls -A "$out" 2>/dev/null)" ]; then
  [ -e "$out/fidelity.json" ] || [ -d "$out/work" ] || die "$out is not empty and holds no earlier fidelity run: choose an empty or new folder"
  [ $overwrite = 1 ] || [ $resume = 1 ] ||
    die "$out holds an earlier run (fidelity.json or work/): --overwrite replaces it, --resume completes it"
fi

# The variants: the product of the --vary lists, each as NAME=VALUE words and a file-name id.
variants=("")
for i in "${!variant_names[@]}"; do
  next=()
  for prefix in "${variants[@]}"; do
    for value in ${variant_values[$i]//,/ }; do
      next+=("${prefix:+$prefix }${variant_names[$i]}=$value")
    done
  done
  variants=("${next[@]}")
done
variant_id() {  # "NAME=VALUE ...": name-value__name-value (file names: letters, digits, _ . -)
  local id="" word
  for word in $1; do id+="${id:+__}${word/=/-}"; done
  echo "${id//[^A-Za-z0-9_.-]/_}"
}
variant_sets() {  # "NAME=VALUE ...": --set NAME=VALUE ...
  local word
  for word in $1; do printf -- '--set\n%s\n' "$word"; done
}

# Check k sets the k-th value of every --vary (the last where a list is shorter) and every --set:
# as many tiny pictures as the longest list has values.
check_dir="$(mktemp -d)"
trap 'rm -rf "$check_dir"' EXIT
longest=0
for i in "${!variant_values[@]}"; do
  read -r -a words <<<"${variant_values[$i]//,/ }"
  [ ${#words[@]} -gt $longest ] && longest=${#words[@]}
done
for ((k = 0; k < longest; k++)); do
  check=()
  for i in "${!variant_names[@]}"; do
    read -r -a words <<<"${variant_values[$i]//,/ }"
    j=$((k < ${#words[@]} ? k : ${#words[@]} - 1))
    check+=(--set "${variant_names[$i]}=${words[$j]}")
  done
  if ! "$wisp" render --width 16 --height 16 --guides 4 --set strands_per_guide=1 "${set_args[@]}" "${check[@]}" \
    --out "$check_dir/check.png" >"$check_dir/log" 2>&1; then
    die "the settings ${check[*]} ${set_args[*]} were refused: $(grep -m1 'wisp' "$check_dir/log" || tail -n1 "$check_dir/log")"
  fi
done

# ---- The jobs ------------------------------------------------------------------------------------
if [ $overwrite = 1 ]; then
  rm -rf "$out/work" "$out/fidelity.md" "$out/fidelity.json" "$out/fidelity.log" "$out/fidelity-images.tar" \
    "$out"/fidelity-*.png
fi
mkdir -p "$out/work"
out="$(cd "$out" && pwd)"
work="$out/work"
log="$work/run.log"
[ $resume = 1 ] || : >"$log"
jobs_file="$work/jobs.txt"
: >"$jobs_file"
: >"$jobs_file.references"
manifest="$work/manifest.tsv"
printf 'kind\tcase\tgroom\tlight\tcolour\tterm\tvariant\treference\tmask\ttest\n' >"$manifest"

groom_args() {  # GROOM: the options that load or grow it
  case "$1" in
  default) [ -n "$guides" ] && printf -- '--guides\n%s\n' "$guides"; true ;;
  sintel) printf -- '%s\n' --head "$sintel_head" --hair "$sintel_hair" --set strands_per_guide=8 ;;
  esac
}
light_args() {  # LIGHT
  case "$1" in
  front) printf -- '%s\n' --light-azimuth 40 --light-elevation 35 ;;
  back) printf -- '%s\n' --light-azimuth 160 --light-elevation 20 ;;
  esac
}
term_args() {  # TERM: all (every light), key (the key light alone), rest (every light but the key)
  case "$1" in
  all) ;;
  key) printf -- '%s\n' --set fill_intensity=0 --set rim_intensity=0 --set ambient=0 ;;
  rest) printf -- '%s\n' --light-intensity 0 ;;
  esac
}
job() {  # OUT.png ARGS...: one `wisp render` (its log beside the picture), a line of the job list
  local png="$1"; shift
  local line name="${png#"$work"/}"
  printf -v line '%q ' "$wisp" render "$@" --out "$png"
  line+=">$(printf '%q' "${png%.png}.log") 2>&1 && echo 'fidelity: rendered $name' >&2"
  line+=" || { echo 'fidelity: failed: ${png%.png}.log' >&2; exit 255; }"
  # wisp writes a picture whole or not at all: with --resume one that is there is not drawn again.
  if [ $resume = 1 ]; then line="[ -f $(printf '%q' "$png") ] || { $line; }"; fi
  # The references first: the longest renders start first when --jobs runs several.
  case "$*" in
  *--reference*) echo "$line" >>"$jobs_file.references" ;;
  *) echo "$line" >>"$jobs_file" ;;
  esac
}

terms_list=(all)
[ $terms = 1 ] && terms_list+=(key rest)
for groom in "${groom_list[@]}"; do
  for light in "${light_list[@]}"; do
    for colour in "${colour_list[@]}"; do
      case="$groom-$light-$colour"
      dir="$work/$case"
      mkdir -p "$dir"
      mapfile -t common < <(groom_args "$groom"; light_args "$light"
        printf -- '%s\n' --set "hair_preset=$colour" --frames "$frames" --width "$width" --height "$height")
      for term in "${terms_list[@]}"; do
        mapfile -t targs < <(term_args "$term")
        prefix="$dir/"
        [ "$term" = all ] || prefix="$dir/$term-"
        job "${prefix}reference.png" --reference --spp "$spp" --sample-seed 1 "${common[@]}" "${targs[@]}" "${set_args[@]}"
        if [ "$term" = all ]; then
          # A second reference of other samples: its distance from the first is the references' own
          # noise in the same metrics, the floor of every error measured against them.
          job "${prefix}reference-seed2.png" --reference --spp "$spp" --sample-seed 2 "${common[@]}" "${set_args[@]}"
          printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' floor "$case" "$groom" "$light" "$colour" all - \
            "${prefix}reference.png" "${prefix}no-hair.png" "${prefix}reference-seed2.png" >>"$manifest"
        fi
        job "${prefix}no-hair.png" "${common[@]}" "${targs[@]}" "${set_args[@]}" --no-hair
        if [ "$term" = all ]; then
          term_variants=("${variants[@]}")
        else
          term_variants=("${variants[0]}")
        fi
        for variant in "${term_variants[@]}"; do
          mapfile -t vs < <(variant_sets "$variant")
          id="$(variant_id "$variant")"
          job "${prefix}rt-$id.png" "${common[@]}" "${targs[@]}" "${set_args[@]}" "${vs[@]}"
          kind=variant
          [ "$term" = all ] || kind=term
          printf '%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\t%s\n' "$kind" "$case" "$groom" "$light" "$colour" "$term" \
            "$variant" "${prefix}reference.png" "${prefix}no-hair.png" "${prefix}rt-$id.png" >>"$manifest"
        done
      done
    done
  done
done
cat "$jobs_file" >>"$jobs_file.references"
mv "$jobs_file.references" "$jobs_file"

total=$(wc -l <"$jobs_file")
echo "fidelity: $total renders ($(grep -c -- '--reference' "$jobs_file") references) at ${width}x$height, $spp samples per pixel, $jobs at once" | tee -a "$log" >&2
start=$SECONDS
# xargs stops at the first job that exits 255 (a failed render: its log is named).
if ! tr '\n' '\0' <"$jobs_file" | xargs -0 -P "$jobs" -n 1 bash -c 'eval "$1"' _ 2> >(tee -a "$log" >&2); then
  echo "fidelity: a render failed (its log is named above; every log is under $work)" >&2
  exit 1
fi
render_s=$((SECONDS - start))
echo "fidelity: renders took $render_s s$([ $resume = 1 ] && echo ' (with --resume: those not drawn before)')" |
  tee -a "$log" >&2

# ---- The measurements ----------------------------------------------------------------------------
start=$SECONDS
compare_one() {  # TEST.png REFERENCE.png NO_HAIR.png: wisp compare's JSON and error image beside TEST
  "$wisp" compare "$1" "$2" --mask "$3" --out "${1%.png}-err.png" --json >"${1%.png}.json" \
    2>"${1%.png}-compare.log" </dev/null ||
    { echo "fidelity: compare failed: $(cat "${1%.png}-compare.log")" >&2; exit 255; }
}
export -f compare_one
export wisp
awk -F'\t' 'NR > 1 {print $10; print $8; print $9}' "$manifest" |
  xargs -d '\n' -P "$jobs" -n 3 bash -c 'compare_one "$@"' _ || { echo "fidelity: a comparison failed" >&2; exit 1; }
echo "fidelity: comparisons took $((SECONDS - start)) s" | tee -a "$log" >&2

devices="$("$wisp" info 2>/dev/null | grep -i '^device [0-9]' | tr '\n' ';' || true)"
"$python" "$root/scripts/fidelity.py" table --manifest "$manifest" --out "$out" --command "$command_line" \
  --devices "$devices" --spp "$spp" --width "$width" --height "$height" --frames "$frames" \
  --render-seconds "$render_s" --pack-mb "$pack_mb" --sets "${sets[*]}" --sheets-by "$sheet_tool" --resumed "$resume"

# ---- Sheets: reference | best | its error | worst | its error, and every variant -------------------
thumb=$((width < 480 ? width : 480))
small=$((width < 320 ? width : 320))
sheet_ffmpeg() {  # OUT.png THUMB_WIDTH ROWS_FILE: each line of ROWS_FILE a row of pictures (tab-separated)
  local sheet="$1" w="$2" rows="$3" r=0 row_pngs=() inputs filter n
  while IFS=$'\t' read -r -a pictures; do
    inputs=()
    filter=""
    n=${#pictures[@]}
    for i in "${!pictures[@]}"; do
      inputs+=(-i "${pictures[$i]}")
      filter+="[$i:v]scale=$w:-2:flags=area[s$i];"
    done
    for i in "${!pictures[@]}"; do filter+="[s$i]"; done
    filter+="hstack=inputs=$n"
    [ "$n" = 1 ] && filter="[0:v]scale=$w:-2:flags=area"
    ffmpeg -nostdin -loglevel error -y "${inputs[@]}" -filter_complex "$filter" "$work/row-$r.png"
    row_pngs+=(-i "$work/row-$r.png")
    r=$((r + 1))
  done <"$rows"
  if [ $r = 1 ]; then
    mv "$work/row-0.png" "$sheet"
  else
    ffmpeg -nostdin -loglevel error -y "${row_pngs[@]}" -filter_complex "vstack=inputs=$r" "$sheet"
  fi
  rm -f "$work"/row-*.png
}
for groom in "${groom_list[@]}"; do
  for kind in best all; do
    rows="$work/sheet-$groom-$kind.tsv"
    [ -s "$rows" ] || continue
    name="$out/fidelity-$groom.png"
    w=$thumb
    [ $kind = all ] && name="$out/fidelity-$groom-all.png" && w=$small
    case $sheet_tool in
    ffmpeg)
      sheet_ffmpeg "${name%.png}.partial.png" "$w" "$rows"
      mv "${name%.png}.partial.png" "$name"
      ;;
    pillow) "$python" "$root/scripts/fidelity.py" sheet --rows "$rows" --width "$w" --out "$name" ;;
    none) ;;
    esac
  done
done
if [ "$sheet_tool" = none ]; then
  echo "fidelity: neither ffmpeg nor python3's Pillow is here: no sheets (fidelity-images.tar holds the pictures)" |
    tee -a "$log" >&2
fi

# ---- The pictures, packed (the list is fidelity.py's: references first) --------------------------
(cd "$work" && tar -cf "$out/fidelity-images.tar.partial" -T pack.txt)
mv "$out/fidelity-images.tar.partial" "$out/fidelity-images.tar"
cp "$log" "$out/fidelity.log"
echo "fidelity: $out/fidelity.md, fidelity.json, fidelity-images.tar ($(du -k "$out/fidelity-images.tar" | cut -f1) KiB), sheets by $sheet_tool; $((SECONDS)) s in all" >&2
