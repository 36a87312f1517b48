#!/usr/bin/env python3
"""Renders the verification report in headless Chromium and checks what a reader would see.

Usage: check_report.py <index.html> [--chromium PATH]

Checks (each failure is listed; exit status 1 if any):
  - every <figure> holds an inline SVG that the browser laid out with a non-zero size and that
    contains drawn paths, or a picture (<img>, a snapshot's PNG) laid out at 50 px or more (no "missing
    figure" or "missing picture" placeholder); every <img> loaded (naturalWidth > 0), a broken one is
    named by its alt text;
  - no tick label repeated along an axis of a figure (e.g. every tick reading 1.25e7);
  - no NaN / inf in the visible text of the page (the cited documentation's prose aside);
  - every link inside the page (contents, studies, citations of docs/) reaches an element of the page;
  - no raw Markdown visible (READMEs and docs/ are rendered, reports/cited_docs.hpp): no table rule |---|,
    no line starting with "# " (up to ######), no **bold**, outside code blocks and inline code.
The page is copied with a small script appended that measures the figures in the browser and writes
the results into the DOM, which Chromium prints (--dump-dom).
"""
import html.parser
import json
import os
import re
import shutil
import subprocess
import sys
import tempfile

PROBE = r"""
<script>
(function () {
  // the visible text without the cited documentation (prose such as "an energy or NaN criterion")
  const cited = document.getElementById('cited');
  if (cited) cited.style.display = 'none';
  const out = {figures: [], images: [], text: document.body.innerText, broken_links: [], cites: 0};
  if (cited) cited.style.display = '';
  // the visible text with the cited documentation, code blocks and inline code left out (a "# comment"
  // line of a shell example is no raw Markdown): the text the raw-Markdown check reads
  const code = Array.from(document.querySelectorAll('pre, code'));
  const shown = code.map(function (e) { return e.style.display; });
  code.forEach(function (e) { e.style.display = 'none'; });
  out.prose = document.body.innerText;
  code.forEach(function (e, k) { e.style.display = shown[k]; });
  // every link inside the page (table of contents, study links, citations) reaches an element
  document.querySelectorAll('a[href^="#"]').forEach(function (a) {
    const id = decodeURIComponent(a.getAttribute('href').slice(1));
    if (!document.getElementById(id)) out.broken_links.push(a.getAttribute('href') + ' (' + a.textContent.slice(0, 40) + ')');
    if (a.classList.contains('cite')) out.cites += 1;
  });
  document.querySelectorAll('figure').forEach(function (fig, k) {
    const svg = fig.querySelector('svg');
    const img = fig.querySelector('img');
    const ib = img ? img.getBoundingClientRect() : {width: 0, height: 0};
    const caption = (fig.querySelector('figcaption') || {}).textContent || ('figure ' + k);
    const r = svg ? svg.getBoundingClientRect() : {width: 0, height: 0};
    const texts = [];
    if (svg) svg.querySelectorAll('text').forEach(function (t) {
      const b = t.getBoundingClientRect();
      const anchor = (t.closest('[text-anchor]') || t).getAttribute('text-anchor') || 'start';
      texts.push({s: t.textContent.trim(), x: Math.round(b.right), cx: Math.round(b.left + b.width / 2),
                  y: Math.round(b.top + b.height / 2), anchor: anchor});
    });
    out.figures.push({caption: caption.trim().slice(0, 120), svg: !!svg, width: r.width, height: r.height,
                      paths: svg ? svg.querySelectorAll('path, polyline').length : 0,  // gnuplot draws paths, bench/suite.py polylines
                      missing: !!fig.querySelector('.missing-figure'), texts: texts,
                      img: img ? {ok: img.complete && img.naturalWidth > 0, width: ib.width, height: ib.height} : null});
  });
  document.querySelectorAll('img').forEach(function (img) {
    out.images.push({src: (img.getAttribute('src') || '').slice(0, 60), alt: img.getAttribute('alt') || '',
                     ok: img.complete && img.naturalWidth > 0});
  });
  const pre = document.createElement('pre');
  pre.id = 'browser-check';
  pre.textContent = JSON.stringify(out);
  document.body.appendChild(pre);
})();
</script>
"""

NUMBER = re.compile(r"^[-+−]?[0-9.]+([eE×x][-+−]?[0-9]+)?(\s*10\s*[-−]?[0-9]+)?%?$")


class PreText(html.parser.HTMLParser):
    def __init__(self):
        super().__init__()
        self.inside = False
        self.data = []

    def handle_starttag(self, tag, attrs):
        if tag == "pre" and ("id", "browser-check") in attrs:
            self.inside = True

    def handle_endtag(self, tag):
        if tag == "pre":
            self.inside = False

    def handle_data(self, data):
        if self.inside:
            self.data.append(data)


def repeated_ticks(texts):
    """Numeric labels sharing an axis (same right edge: y ticks; same centre line: x ticks)."""
    problems = []
    numeric = [t for t in texts if t["s"] and NUMBER.match(t["s"].replace(" ", ""))]
    for key, what in (("x", "y axis"), ("y", "x axis")):
        groups = {}
        for t in numeric:
            if what == "y axis" and t["anchor"] != "end":
                continue
            if what == "x axis" and t["anchor"] != "middle":
                continue
            groups.setdefault(t[key], []).append(t["s"])
        for labels in groups.values():
            if len(labels) >= 2 and len(set(labels)) < len(labels):
                dup = sorted({l for l in labels if labels.count(l) > 1})
                problems.append(f"{what}: tick label(s) {', '.join(dup)} repeated among {labels}")
    return problems


RAW_MARKDOWN = (("table rule", re.compile(r"\|\s*:?-{3,}:?\s*\|")),
                ("heading", re.compile(r"^[ \t]*#{1,6} \S", re.M)),
                ("bold", re.compile(r"\*\*[^*\s](?:[^*\n]*[^*\s])?\*\*")))


def raw_markdown(text):
    """Markdown a reader sees as written (not rendered): a table rule |---|, a line "# heading", **bold**."""
    problems = []
    for what, pattern in RAW_MARKDOWN:
        for m in list(pattern.finditer(text))[:5]:
            start = max(0, m.start() - 40)
            problems.append(f"raw Markdown ({what}) in the page: …" + text[start:m.end() + 40].replace("\n", " ") + "…")
    return problems


def main():
    args = sys.argv[1:]
    chromium = shutil.which("chromium") or shutil.which("chromium-browser") or "chromium"
    if "--chromium" in args:
        i = args.index("--chromium")
        chromium = args[i + 1]
        del args[i:i + 2]
    if len(args) != 1:
        print(__doc__)
        return 2
    page = os.path.abspath(args[0])
    if not os.path.exists(page):
        print(f"{page}: no such report (run the verification suite first)")
        return 1
    with open(page, encoding="utf-8") as f:
        text = f.read()
    probed = text.replace("</body>", PROBE + "</body>") if "</body>" in text else text + PROBE
    folder = tempfile.mkdtemp(prefix="dem2d-browser-")
    try:
        copy = os.path.join(os.path.dirname(page), ".browser-check.html")
        with open(copy, "w", encoding="utf-8") as f:  # next to the page: relative links still resolve
            f.write(probed)
        cmd = [chromium, "--headless", "--no-sandbox", "--disable-gpu", "--allow-file-access-from-files",
               f"--user-data-dir={folder}", "--virtual-time-budget=5000", "--dump-dom", "file://" + copy]
        run = subprocess.run(cmd, capture_output=True, text=True, timeout=120)
        os.remove(copy)
    finally:
        shutil.rmtree(folder, ignore_errors=True)
    parser = PreText()
    parser.feed(run.stdout)
    if not parser.data:
        print(f"chromium produced no measurement (exit {run.returncode}): {run.stderr[-800:]}")
        return 1
    result = json.loads("".join(parser.data))
    problems = []
    for fig in result["figures"]:
        name = fig["caption"]
        if fig["missing"] or not (fig["svg"] or fig["img"]):
            problems.append(f"figure not rendered: {name}")
            continue
        if not fig["svg"]:  # a picture (a snapshot's PNG): loaded (the image list says if not) and laid out
            if fig["img"]["ok"] and (fig["img"]["width"] < 50 or fig["img"]["height"] < 50):
                problems.append(f"picture laid out at {fig['img']['width']:.0f} x {fig['img']['height']:.0f} px: {name}")
            continue
        if fig["width"] < 50 or fig["height"] < 50:
            problems.append(f"figure laid out at {fig['width']:.0f} x {fig['height']:.0f} px: {name}")
        if fig["paths"] < 3:
            problems.append(f"figure has no drawn curves ({fig['paths']} paths): {name}")
        for p in repeated_ticks(fig["texts"]):
            problems.append(f"{name}: {p}")
    for img in result["images"]:
        if not img["ok"]:
            problems.append(f"broken image: {img['alt'] or img['src']}")
    for link in result["broken_links"][:20]:
        problems.append(f"link to nothing in the page: {link}")
    for m in re.finditer(r"(?<![A-Za-z])(nan|NaN|NAN|-?inf|-?Inf|-?INF|Infinity)(?![A-Za-z])", result["text"]):
        start = max(0, m.start() - 60)
        problems.append("NaN/inf in the page: …" + result["text"][start:m.end() + 20].replace("\n", " ") + "…")
        if len(problems) > 40:
            break
    problems += raw_markdown(result["prose"])
    print(f"browser check: {len(result['figures'])} figures, {len(result['images'])} images, "
          f"{len(result['text'])} characters of text, {result['cites']} citations linked to the cited documentation")
    for p in problems:
        print("  FAIL " + p)
    if not problems:
        print("  all figures and pictures rendered; no repeated tick labels; no NaN/inf; no raw Markdown")
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main())
