# The whole set-up on a fresh machine: `make demo` and `make test`.
# Each creates .venv and installs what it needs; re-running only reinstalls
# when pyproject.toml changed. kreisel is installed editable, so every target
# compiles into .numba_cache/<state of the sources> (see kreisel._compiled):
# no target runs machine code compiled before an edit.
PYTHON ?= python3
VENV := .venv
PY := $(VENV)/bin/python

.PHONY: demo test bench clean docs

$(VENV)/.created:
	$(PYTHON) -m venv $(VENV)
	$(PY) -m pip install --quiet --upgrade pip
	touch $@

# every target installs every feature (the extras); `pip install kreisel` alone is the core
$(VENV)/.installed-run: pyproject.toml $(VENV)/.created
	$(PY) -m pip install --quiet -e ".[all]"
	touch $@

# the tests build the documentation too (tests/docs/test_docs_build.py)
$(VENV)/.installed-dev: pyproject.toml $(VENV)/.created
	$(PY) -m pip install --quiet -e ".[all,dev,docs]"
	touch $@

$(VENV)/.installed-docs: pyproject.toml $(VENV)/.created
	$(PY) -m pip install --quiet -e ".[all,docs]"
	touch $@

demo: $(VENV)/.installed-run
	$(PY) -m kreisel tour --out tour --force

test: $(VENV)/.installed-dev docs/node_modules/.installed
	$(PY) -m pytest -n 2 -q

$(VENV)/.installed-bench: pyproject.toml $(VENV)/.created
	$(PY) -m pip install --quiet -e ".[all,dev,bench]"
	touch $@

bench: $(VENV)/.installed-bench
	$(PY) bench/run_all.py

# MathJax, served with the pages so that they render equations offline
docs/node_modules/.installed: docs/package.json docs/package-lock.json
	cd docs && npm ci --no-audit --no-fund
	touch $@

# English (the source) and its Chinese translation (docs/locale), side by side; the second build finds the gallery
# already run by the first (sphinx-gallery skips examples whose source is unchanged)
docs: $(VENV)/.installed-docs docs/node_modules/.installed
	MPLBACKEND=Agg $(PY) -m sphinx -b html -W -n --keep-going docs docs/_build/html/en
	MPLBACKEND=Agg $(PY) -m sphinx -b html -W -n --keep-going -D language=zh_CN docs docs/_build/html/zh_CN

# the pages translated so far (tests/docs/test_translations.py checks that their catalogs are complete);
# auto_examples/* are the gallery's pages, which sphinx-gallery writes from examples/ before Sphinx reads them
TRANSLATED := index getting_started theory/index theory/1_configuration theory/2_rotation_group theory/3_angular_velocity theory/4_fixed_point theory/5_euler_top theory/6_lagrange_top theory/7_kovalevskaya theory/8_noninertial theory/appendix
TRANSLATED += user_guide/index user_guide/01_description user_guide/02_coordinates user_guide/03_angular_velocity user_guide/03b_attitude_estimation user_guide/04_fixed_point user_guide/05_euler_top user_guide/05b_phone_laboratory user_guide/06_lagrange_top user_guide/07_kovalevskaya user_guide/08_noninertial user_guide/appendix coming_from
TRANSLATED += auto_examples/index auto_examples/plot_01_euler_angles auto_examples/plot_02_gimbal_lock auto_examples/plot_03_bortz auto_examples/plot_04_centrodes auto_examples/plot_05_inertia_ellipsoid auto_examples/plot_06_tennis_racket auto_examples/plot_06b_phone_laboratory auto_examples/plot_06c_separatrix_accuracy auto_examples/plot_07_poinsot auto_examples/plot_08_lagrange_top auto_examples/plot_09_kovalevskaya auto_examples/plot_10_eastward_deflection auto_examples/plot_11_foucault auto_examples/plot_12_coning auto_examples/plot_13_integrators

# after editing a translated English page: update its catalog, then translate what became empty or fuzzy
.PHONY: docs-po
docs-po: $(VENV)/.installed-docs docs/node_modules/.installed
	rm -rf docs/_build/gettext
	MPLBACKEND=Agg $(PY) -m sphinx -b gettext -q docs docs/_build/gettext $(TRANSLATED:%=docs/%.rst)
	$(PY) -m sphinx_intl update -p docs/_build/gettext -d docs/locale -l zh_CN -w 0

clean:
	rm -rf $(VENV) build src/*.egg-info .numba_cache

# The viewer's front end (kreisel serve, kreisel.show): three.js bundled by esbuild into src/kreisel/web/static/
# (widget.js with three.js and the scene; viewer.js, the page logic, imports it).
# The bundle is committed (an installed kreisel serves it without Node.js); after editing web/, run
# `make web` and commit the new bundle: tests/web/test_bundle.py fails while it is stale.
.PHONY: web
WEB_BUNDLE := src/kreisel/web/static/viewer.js

web/node_modules/.installed: web/package.json web/package-lock.json
	cd web && npm ci --no-audit --no-fund
	touch $@

$(WEB_BUNDLE): web/node_modules/.installed web/build.mjs $(wildcard web/src/*.js)
	cd web && npm run build

web: $(WEB_BUNDLE)
