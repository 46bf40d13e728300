// Bundle the front end into the Python package: src/kreisel/web/static/{widget.js, viewer.js, BUILD.json}.
// widget.js is the notebook widget of kreisel.show (an anywidget module, loaded from one string, so it holds
// three.js and the scene); viewer.js is the page logic of `kreisel serve` and imports the scene from
// ./widget.js at run time, so three.js is shipped once. The page itself (static/index.html, favicon.svg)
// needs no build and lives only in the package.
// The bundle is committed, so that an installed kreisel serves the viewer without Node.js; BUILD.json holds
// the hash of the sources it was built from, which tests/web/test_bundle.py compares with web/.
// KREISEL_WEB_OUT=dir writes the bundle elsewhere (the test rebuilds into a temporary folder).
import { build } from "esbuild";
import { createHash } from "node:crypto";
import { mkdirSync, readFileSync, readdirSync, writeFileSync } from "node:fs";

const here = (path) => new URL(path, import.meta.url).pathname;
const out = (process.env.KREISEL_WEB_OUT || here("../src/kreisel/web/static")).replace(/\/?$/, "/");

// the files the bundle is made from, in a fixed order, with their contents
function sources() {
  const names = ["build.mjs", "package-lock.json",
    ...readdirSync(here("src")).filter((n) => n.endsWith(".js")).sort().map((n) => `src/${n}`)];
  const digest = createHash("sha256");
  for (const name of names) {
    digest.update(name + "\0");
    digest.update(readFileSync(here(name)).toString("utf8").replace(/\r\n/g, "\n"));
    digest.update("\0");
  }
  return { files: names, sha256: digest.digest("hex") };
}

// main.js's import of ./widget.js stays an import of the sibling file
const widgetIsSibling = {
  name: "widget-is-sibling",
  setup(b) {
    b.onResolve({ filter: /^\.\/widget\.js$/ }, (args) =>
      (args.importer.endsWith("main.js") ? { path: "./widget.js", external: true } : undefined));
  },
};

mkdirSync(out, { recursive: true });
for (const [entry, file, plugins] of [["widget", "widget.js", []], ["main", "viewer.js", [widgetIsSibling]]]) {
  await build({
    entryPoints: [here(`src/${entry}.js`)],
    bundle: true,
    minify: true,
    format: "esm",
    target: "es2020",
    // template literals lowered to plain strings: three.js's multi-line GLSL chunks would otherwise stay line by
    // line in the committed bundle, where they read as thousands of repeated source lines
    supported: { "template-literal": false },
    outfile: out + file,
    plugins,
    logLevel: "warning",
  });
}
writeFileSync(out + "BUILD.json", JSON.stringify(sources(), null, 1) + "\n");
