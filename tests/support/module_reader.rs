//! The reader behind `tests/module_graph.rs`: a crate's modules, their `use` lines and paths,
//! resolved to the files that define what they name, and the loops between those files.

use super::rust_tokens::{is_ident, matching, tokens, use_tree, visibility_before};
use std::collections::{BTreeMap, BTreeSet};
use std::fs;
use std::path::{Path, PathBuf};

/// A module path inside a crate: `[]` is the crate root, `["scene", "builder"]` is
/// `crate::scene::builder`.
pub type ModPath = Vec<String>;

/// One name a `use` brings into a module.
#[derive(Clone, Debug)]
struct UseItem {
    /// The path as written, without the final `*` of a glob.
    path: Vec<String>,
    /// The name it is known by here (`None` for a glob).
    name: Option<String>,
    public: bool,
    line: usize,
}

/// What the reader learnt about one module.
#[derive(Debug, Default)]
struct Module {
    file: PathBuf,
    children: BTreeSet<String>,
    uses: Vec<UseItem>,
    defines: BTreeSet<String>,
    /// Paths in code (not in `use` lines), with their lines.
    code_paths: Vec<(Vec<String>, usize)>,
    /// Identifiers used in code (not in `use` lines).
    code_idents: BTreeSet<String>,
    test_only: bool,
}

/// Every module of one crate.
pub struct Crate {
    name: String,
    root: PathBuf,
    modules: BTreeMap<ModPath, Module>,
}

const ITEM_KEYWORDS: &[&str] = &[
    "struct",
    "enum",
    "fn",
    "trait",
    "type",
    "const",
    "static",
    "union",
    "macro_rules",
];

impl Crate {
    pub fn read(name: &str, src: &Path) -> Crate {
        let mut krate = Crate {
            name: name.into(),
            root: src.to_path_buf(),
            modules: BTreeMap::new(),
        };
        krate.read_file(Vec::new(), &src.join("lib.rs"), false);
        krate
    }

    fn read_file(&mut self, path: ModPath, file: &Path, test_only: bool) {
        let source = fs::read_to_string(file).unwrap_or_else(|e| panic!("{}: {e}", file.display()));
        let toks = tokens(&source);
        let mut stack: Vec<(ModPath, usize, bool)> = vec![(path.clone(), 0, test_only)];
        self.modules.entry(path.clone()).or_default();
        self.modules.get_mut(&path).unwrap().file = file.to_path_buf();
        self.modules.get_mut(&path).unwrap().test_only = test_only;
        let mut depth = 0usize;
        let mut child_files = Vec::new();
        let mut i = 0;
        let mut cfg_test = false;
        while i < toks.len() {
            let t = toks[i].text.as_str();
            let (current, _, current_test) = stack.last().unwrap().clone();
            match t {
                "#" => {
                    // An attribute: note #[cfg(test)], skip the rest.
                    let end = matching(&toks, i + 1);
                    let body: Vec<&str> = toks[i + 1..=end].iter().map(|t| t.text.as_str()).collect();
                    if body == ["[", "cfg", "(", "test", ")", "]"] {
                        cfg_test = true;
                    }
                    i = end + 1;
                    continue;
                }
                "{" => depth += 1,
                "}" => {
                    depth -= 1;
                    if stack.len() > 1 && stack.last().unwrap().1 == depth {
                        stack.pop();
                    }
                }
                "mod" if toks.get(i + 1).is_some_and(|t| is_ident(&t.text)) => {
                    let child = toks[i + 1].text.clone();
                    let mut child_path = current.clone();
                    child_path.push(child.clone());
                    self.modules
                        .get_mut(&current)
                        .unwrap()
                        .children
                        .insert(child.clone());
                    let test = current_test || cfg_test;
                    if toks.get(i + 2).map(|t| t.text.as_str()) == Some("{") {
                        let m = self.modules.entry(child_path.clone()).or_default();
                        m.file = file.to_path_buf();
                        m.test_only = test;
                        stack.push((child_path, depth, test));
                        depth += 1;
                        i += 3;
                    } else {
                        child_files.push((child_path, test));
                        i += 3;
                    }
                    cfg_test = false;
                    continue;
                }
                "use" => {
                    let public = i > 0 && visibility_before(&toks, i);
                    let end = (i..toks.len()).find(|&j| toks[j].text == ";").unwrap();
                    let mut items = Vec::new();
                    use_tree(&toks[i + 1..end], &[], &mut items);
                    let module = self.modules.get_mut(&current).unwrap();
                    for (path, name) in items {
                        module.uses.push(UseItem {
                            path,
                            name,
                            public,
                            line: toks[i].line,
                        });
                    }
                    cfg_test = false;
                    i = end + 1;
                    continue;
                }
                _ if ITEM_KEYWORDS.contains(&t) => {
                    cfg_test = false;
                    if let Some(name) = toks.get(i + 1).filter(|t| is_ident(&t.text)) {
                        let name = if t == "macro_rules" {
                            toks.get(i + 2).map(|t| t.text.clone())
                        } else {
                            Some(name.text.clone())
                        };
                        if let Some(name) = name {
                            self.modules.get_mut(&current).unwrap().defines.insert(name);
                        }
                    }
                }
                _ if is_ident(t) => {
                    // A path in code: ident (:: ident)*, not preceded by `::`.
                    let after_colons = i > 0 && toks[i - 1].text == "::";
                    let module = self.modules.get_mut(&current).unwrap();
                    module.code_idents.insert(t.to_string());
                    if !after_colons && toks.get(i + 1).is_some_and(|t| t.text == "::") {
                        let mut path = vec![t.to_string()];
                        let mut j = i + 1;
                        while toks.get(j).is_some_and(|t| t.text == "::")
                            && toks.get(j + 1).is_some_and(|t| is_ident(&t.text))
                        {
                            path.push(toks[j + 1].text.clone());
                            module.code_idents.insert(toks[j + 1].text.clone());
                            j += 2;
                        }
                        module.code_paths.push((path, toks[i].line));
                        i = j;
                        continue;
                    }
                }
                ";" => cfg_test = false,
                _ => {}
            }
            i += 1;
        }
        for (child_path, test) in child_files {
            let dir = if file.file_name().is_some_and(|n| n == "lib.rs" || n == "mod.rs") {
                file.parent().unwrap().to_path_buf()
            } else {
                file.with_extension("")
            };
            let name = child_path.last().unwrap();
            let flat = dir.join(format!("{name}.rs"));
            let nested = dir.join(name).join("mod.rs");
            let child_file = if flat.exists() { flat } else { nested };
            self.read_file(child_path, &child_file, test);
        }
    }

    /// The file a module lives in, relative to the crate's `src`.
    fn file_of(&self, path: &ModPath) -> String {
        let file = &self.modules[path].file;
        file.strip_prefix(&self.root)
            .unwrap_or(file)
            .display()
            .to_string()
    }

    /// Makes `path`, as written in module `context`, absolute (`crate::…`), or `None` when it
    /// leads out of the crate.
    fn absolute(&self, context: &ModPath, path: &[String]) -> Option<Vec<String>> {
        let first = path.first()?;
        let mut base = match first.as_str() {
            "crate" => Vec::new(),
            "self" => context.clone(),
            "super" => {
                let mut base = context.clone();
                let mut rest = path;
                while rest.first().is_some_and(|s| s == "super") {
                    base.pop()?;
                    rest = &rest[1..];
                }
                base.extend(rest.iter().cloned());
                return Some(base);
            }
            _ if self.modules[context].children.contains(first) => {
                let mut base = context.clone();
                base.push(first.clone());
                base.extend(path[1..].iter().cloned());
                return Some(base);
            }
            _ => {
                // A name a `use` here brought in.
                let item = self.modules[context]
                    .uses
                    .iter()
                    .find(|u| u.name.as_deref() == Some(first.as_str()))?;
                if item.path.len() == 1 {
                    // `use glam;`: an outside crate.
                    return None;
                }
                let mut base = self.absolute(context, &item.path)?;
                base.extend(path[1..].iter().cloned());
                return Some(base);
            }
        };
        base.extend(path[1..].iter().cloned());
        Some(base)
    }

    /// The module that defines what the absolute `path` names, and whether the path went
    /// through a re-export (a `use`) on the way.
    fn defining_module(&self, path: &[String], hops: usize) -> Option<(ModPath, bool)> {
        if hops > 16 {
            return None;
        }
        let mut module: ModPath = Vec::new();
        for (k, segment) in path.iter().enumerate() {
            if self.modules[&module].children.contains(segment) {
                module.push(segment.clone());
                continue;
            }
            let here = &self.modules[&module];
            if here.defines.contains(segment) {
                return Some((module, false));
            }
            if let Some(item) = here
                .uses
                .iter()
                .find(|u| u.name.as_deref() == Some(segment.as_str()))
            {
                let mut target = self.absolute(&module, &item.path)?;
                target.extend(path[k + 1..].iter().cloned());
                return self.defining_module(&target, hops + 1).map(|(m, _)| (m, true));
            }
            for glob in here.uses.iter().filter(|u| u.name.is_none()) {
                if let Some(mut target) = self.absolute(&module, &glob.path) {
                    target.extend(path[k..].iter().cloned());
                    if let Some((m, _)) = self.defining_module(&target, hops + 1)
                        && self.modules[&m].defines.contains(segment)
                    {
                        return Some((m, true));
                    }
                }
            }
            return Some((module, false));
        }
        Some((module, false))
    }

    /// Edges between files: (from, to) → the first line that makes it, and the imports that go
    /// through a re-export instead of naming the defining module.
    pub fn edges(&self) -> (BTreeMap<(String, String), String>, Vec<String>) {
        let mut edges = BTreeMap::new();
        let mut indirect = Vec::new();
        for (path, module) in &self.modules {
            if module.test_only {
                continue;
            }
            let from = self.file_of(path);
            let mut add =
                |written: &[String], line: usize, check_direct: bool, edges: &mut BTreeMap<_, _>| {
                    let Some(absolute) = self.absolute(path, written) else {
                        return;
                    };
                    let Some((target, via_reexport)) = self.defining_module(&absolute, 0) else {
                        return;
                    };
                    let to = self.file_of(&target);
                    if check_direct && via_reexport {
                        indirect.push(format!(
                            "{from}:{line} imports {} (defined in {to})",
                            written.join("::")
                        ));
                    }
                    if to != from {
                        edges
                            .entry((from.clone(), to))
                            .or_insert_with(|| format!("{from}:{line} `{}`", written.join("::")));
                    }
                };
            for item in &module.uses {
                let used_here =
                    !item.public || item.name.as_ref().is_some_and(|n| module.code_idents.contains(n));
                if used_here {
                    let mut written = item.path.clone();
                    if written.last().is_some_and(|l| l == "self") {
                        written.pop();
                    }
                    add(&written, item.line, !item.public, &mut edges);
                }
            }
            for (written, line) in &module.code_paths {
                // A path from a name a `use` brought in is checked at that `use`.
                let from_use = module.uses.iter().any(|u| u.name.as_ref() == written.first());
                add(written, *line, !from_use, &mut edges);
            }
        }
        (edges, indirect)
    }

    /// Every cycle between distinct files, one per strongly connected group, each as
    /// `a.rs → b.rs → a.rs` with the line that makes each step.
    pub fn loops(&self) -> Vec<String> {
        let (edges, _) = self.edges();
        let mut next: BTreeMap<&str, Vec<&str>> = BTreeMap::new();
        for (from, to) in edges.keys() {
            next.entry(from).or_default().push(to);
        }
        let mut reported: BTreeSet<BTreeSet<String>> = BTreeSet::new();
        let mut out = Vec::new();
        for start in next.keys() {
            // The shortest way back to `start`, by breadth-first search.
            let mut previous: BTreeMap<&str, &str> = BTreeMap::new();
            let mut frontier = vec![*start];
            let mut found = None;
            'search: while !frontier.is_empty() {
                let mut following = Vec::new();
                for node in frontier {
                    for &to in next.get(node).map(Vec::as_slice).unwrap_or(&[]) {
                        if to == *start {
                            found = Some(node);
                            break 'search;
                        }
                        if !previous.contains_key(to) {
                            previous.insert(to, node);
                            following.push(to);
                        }
                    }
                }
                frontier = following;
            }
            let Some(last) = found else { continue };
            let mut cycle = vec![last];
            while let Some(&p) = previous.get(cycle.last().unwrap()) {
                cycle.push(p);
            }
            cycle.reverse();
            if cycle[0] != *start {
                cycle.insert(0, start);
            }
            let members: BTreeSet<String> = cycle.iter().map(|s| s.to_string()).collect();
            if !reported.insert(members) {
                continue;
            }
            cycle.push(start);
            let steps: Vec<String> = cycle
                .windows(2)
                .map(|w| edges[&(w[0].to_string(), w[1].to_string())].clone())
                .collect();
            out.push(format!(
                "{}: {}  [{}]",
                self.name,
                cycle.join(" → "),
                steps.join("; ")
            ));
        }
        out
    }
}
