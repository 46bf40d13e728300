// Bundle the viewer into the Python package: src/kreisel/web/static/{index.html, viewer.js}.
import { build } from "esbuild";
import { copyFileSync, mkdirSync } from "node:fs";

const out = new URL("../src/kreisel/web/static/", import.meta.url).pathname;
mkdirSync(out, { recursive: true });
await build({
  entryPoints: [new URL("src/main.js", import.meta.url).pathname],
  bundle: true,
  minify: true,
  format: "esm",
  target: "es2020",
  outfile: out + "viewer.js",
  logLevel: "warning",
});
copyFileSync(new URL("index.html", import.meta.url).pathname, out + "index.html");
