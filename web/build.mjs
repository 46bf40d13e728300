// Bundle the viewer into the Python package: src/kreisel/web/static/{index.html, viewer.js, widget.js, favicon.svg, BUILD.json}.
// The bundle is committed, so that an installed kreisel serves the viewer without Node.js; BUILD.json holds
// the hash of the sources it was built from, which tests/web/test_bundle.py compares with web/.
// KREISEL_WEB_OUT=dir writes the bundle elsewhere (the test rebuilds into a temporary folder).
import { build } from "esbuild";
import { createHash } from "node:crypto";
import { copyFileSync, mkdirSync, readFileSync, readdirSync, writeFileSync } from "node:fs";

const here = (path) => new URL(path, import.meta.url).pathname;
const out = (process.env.KREISEL_WEB_OUT || here("../src/kreisel/web/static")).replace(/\/?$/, "/");

// the files the bundle is made from, in a fixed order, with their contents
function sources() {
  const names = ["build.mjs", "index.html", "favicon.svg", "package-lock.json",
    ...readdirSync(here("src")).filter((n) => n.endsWith(".js")).sort().map((n) => `src/${n}`)];
  const digest = createHash("sha256");
  for (const name of names) {
    digest.update(name + "\0");
    digest.update(readFileSync(here(name)).toString("utf8").replace(/\r\n/g, "\n"));
    digest.update("\0");
  }
  return { files: names, sha256: digest.digest("hex") };
}

mkdirSync(out, { recursive: true });
// the viewer's page, and the notebook widget of kreisel.show (the same scene, as an anywidget module)
for (const name of ["main", "widget"]) {
  await build({
    entryPoints: [here(`src/${name}.js`)],
    bundle: true,
    minify: true,
    format: "esm",
    target: "es2020",
    outfile: out + (name === "main" ? "viewer.js" : "widget.js"),
    logLevel: "warning",
  });
}
copyFileSync(here("index.html"), out + "index.html");
copyFileSync(here("favicon.svg"), out + "favicon.svg");
writeFileSync(out + "BUILD.json", JSON.stringify(sources(), null, 1) + "\n");
