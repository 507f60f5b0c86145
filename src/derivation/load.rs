//! Reading derivation files: TOML text → checked [`DerivationFile`]s. Every mistake
//! becomes a [`Diagnostic`] naming the file, line and column; nothing panics.

use super::model::ParamBox;
use super::model::{
    Assumption, AssumptionKind, Check, Claim, Correction, Curve, Definition, DerivationFile,
    Drafted, Figure, Grid, ScalarClaim, Side, Stated, Strategy, TieKind, TiedSymbol, ToComplete,
    Transcript, Use, Verdict, MAX_NESTING,
};
use super::notation::{self, Notation};
use super::raw::{NotationValue, RawClaim, RawFigure, RawFile, RawStated, S};
use super::spans::{content_map, sub_origin};
use crate::algebra::tensor::{assignment_count_saturating, MAX_COMPONENTS};
use crate::kernel::Rational;
use crate::lang::check::{letters, RESERVED};
use crate::lang::matrix::{shape_words, MatrixOp, MatrixRead};
use crate::lang::parser::ExprKind;
use crate::lang::{
    parse_expr, Decls, DefSig, Diagnostic, ErrorKind, LangError, Origin, Scope, SourceFile, Span,
};
use crate::lang::{Node, NodeKind};
use std::collections::{BTreeMap, BTreeSet};
use std::ops::Range;
use std::path::{Path, PathBuf};
use std::sync::Arc;
use toml::Spanned;

/// How the loader's refusal of sides with different free indices begins: an equation so
/// printed is ill-formed, and `draft` takes it to tie no symbols.
pub(crate) const DIFFERENT_FREE_INDICES: &str = "the sides have different free indices";
/// How the error of a definition whose free indices differ from its name's begins.
pub(crate) const DEFINED_WITH_INDICES: &str = "is defined with indices";

/// Why derivation files could not be read.
#[derive(Debug, thiserror::Error)]
pub enum LoadError {
    /// The file or directory could not be read at all.
    #[error("error: cannot read {path}: {message}")]
    Io { path: String, message: String },
    /// The file was read but is malformed.
    #[error("{}", paragraphs(.0))]
    Invalid(Vec<Diagnostic>),
}

/// Diagnostics one after another, a blank line between them.
fn paragraphs(ds: &[Diagnostic]) -> String {
    let parts: Vec<String> = ds.iter().map(ToString::to_string).collect();
    parts.join("\n\n")
}

impl From<Diagnostic> for LoadError {
    fn from(d: Diagnostic) -> Self {
        LoadError::Invalid(vec![d])
    }
}

/// Whether declared index slots are letters, each used once (`sigma_ij`, not `w_ii`).
pub(super) fn distinct_letters(idx: &[char]) -> bool {
    idx.iter().all(char::is_ascii_alphabetic)
        && idx.iter().collect::<std::collections::BTreeSet<_>>().len() == idx.len()
}

/// Reads every `*.toml` file directly in `dir` (sorted by name), and checks that
/// claim ids are unique across them.
pub fn load_dir(dir: &Path) -> Result<Vec<DerivationFile>, LoadError> {
    load_files(&toml_files(dir)?)
}

/// The `*.toml` files directly in `dir`, sorted by name; an error when there are none,
/// or when a `*.toml` entry is not a regular file (a FIFO would block the run, a device
/// never end it, and skipping it would say nothing).
pub fn toml_files(dir: &Path) -> Result<Vec<PathBuf>, LoadError> {
    let io = |e: std::io::Error| LoadError::Io {
        path: dir.display().to_string(),
        message: e.to_string(),
    };
    let mut paths: Vec<_> = std::fs::read_dir(dir)
        .map_err(io)?
        .filter_map(Result::ok)
        .map(|e| e.path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    paths.sort();
    if let Some(odd) = paths.iter().find(|p| !p.is_file()) {
        return Err(LoadError::Io {
            path: odd.display().to_string(),
            message:
                "not a regular file (a directory, FIFO, socket or device); refusing to read it"
                    .into(),
        });
    }
    if paths.is_empty() {
        return Err(LoadError::Io {
            path: dir.display().to_string(),
            message: "no derivation files (*.toml) in this directory".into(),
        });
    }
    Ok(paths)
}

/// Reads the given files in order, checking that claim ids are unique across them.
pub fn load_files(paths: &[impl AsRef<Path> + Sync]) -> Result<Vec<DerivationFile>, LoadError> {
    unique_ids(
        crate::parallel::in_index_order(paths.len(), |k| load_file_with_ids(paths[k].as_ref()))
            .into_iter(),
    )
}

/// Derivation files given as (label, text) pairs — the corpus embedded in the binary —
/// in order, with claim ids unique across them.
pub fn load_texts(sources: &[(&str, &str)]) -> Result<Vec<DerivationFile>, LoadError> {
    unique_ids(
        crate::parallel::in_index_order(sources.len(), |k| {
            let (label, text) = sources[k];
            Loader::new(SourceFile::new(label, text)).run()
        })
        .into_iter(),
    )
}

/// A definition within [`MAX_NESTING`], or a located error.
fn bounded(def: Definition) -> Result<Definition, Diagnostic> {
    if def.depth <= MAX_NESTING {
        return Ok(def);
    }
    Err(def
        .origin
        .diagnostic(
            Span::new(0, def.text.len()),
            format!(
                "this definition nests {} levels deep through the definitions it reads, more than {MAX_NESTING}",
                def.depth
            ),
        )
        .with_help("shorten the chain of definitions, or write the expression out"))
}

fn unique_ids(
    loaded: impl Iterator<Item = Result<(DerivationFile, Vec<(String, IdDiag)>), LoadError>>,
) -> Result<Vec<DerivationFile>, LoadError> {
    let mut files = Vec::new();
    let mut seen: BTreeMap<String, String> = BTreeMap::new();
    for read in loaded {
        let (file, ids) = read?;
        for (id, diag) in ids {
            if let Some(first) = seen.get(&id) {
                return Err(
                    diag(format!("duplicate claim id `{id}` (first used in {first})"))
                        .with_help(
                            "claim ids are unique across the files checked together; rename one",
                        )
                        .into(),
                );
            }
            seen.insert(id, file.path.clone());
        }
        files.push(file);
    }
    super::uses::link(&files)?;
    Ok(files)
}

type IdDiag = Box<dyn Fn(String) -> Diagnostic + Send>;

/// The largest derivation file read, in bytes (the paper's largest is about 20 kB).
pub const MAX_FILE_BYTES: u64 = 4 << 20;
/// The longest claim id, in characters.
pub const MAX_ID_CHARS: usize = 100;

/// The bytes of a derivation file: a regular file (never a device such as /dev/zero,
/// a FIFO that could block forever, or a directory) of at most [`MAX_FILE_BYTES`].
pub fn read_bounded(path: &Path) -> Result<Vec<u8>, LoadError> {
    use std::io::Read;
    let label = path.display().to_string();
    let io = |message: String| LoadError::Io {
        path: label.clone(),
        message,
    };
    let too_big = || {
        io(format!(
            "larger than the {} MiB a derivation file may have",
            MAX_FILE_BYTES >> 20
        ))
    };
    if is_stdin(path) {
        // Read once, however often the file is read (`--only` reads files twice).
        static STDIN: std::sync::OnceLock<Result<Vec<u8>, Arc<std::io::Error>>> =
            std::sync::OnceLock::new();
        let read = STDIN.get_or_init(|| {
            let mut bytes = Vec::new();
            std::io::stdin()
                .lock()
                .take(MAX_FILE_BYTES + 1)
                .read_to_end(&mut bytes)
                .map(|_| bytes)
                .map_err(Arc::new)
        });
        let bytes = read.clone().map_err(|e| io(e.to_string()))?;
        if bytes.len() as u64 > MAX_FILE_BYTES {
            return Err(too_big());
        }
        return Ok(bytes);
    }
    let meta = std::fs::metadata(path).map_err(|e| io(e.to_string()))?;
    if !meta.is_file() {
        let what = if meta.is_dir() {
            "a directory"
        } else {
            "not a regular file (a device, FIFO or socket)"
        };
        return Err(io(format!(
            "{what}; derivation files are regular files (use --dir for a directory)"
        )));
    }
    if meta.len() > MAX_FILE_BYTES {
        return Err(too_big());
    }
    let mut bytes = Vec::new();
    std::fs::File::open(path)
        .and_then(|f| f.take(MAX_FILE_BYTES + 1).read_to_end(&mut bytes))
        .map_err(|e| io(e.to_string()))?;
    if bytes.len() as u64 > MAX_FILE_BYTES {
        return Err(too_big());
    }
    Ok(bytes)
}

/// `-` names standard input.
pub fn is_stdin(path: &Path) -> bool {
    path.as_os_str() == "-"
}

fn load_file_with_ids(path: &Path) -> Result<(DerivationFile, Vec<(String, IdDiag)>), LoadError> {
    let label = if is_stdin(path) {
        "<stdin>".to_owned()
    } else {
        path.display().to_string()
    };
    let bytes = read_bounded(path)?;
    let text = match String::from_utf8(bytes) {
        Ok(t) => t,
        Err(e) => {
            let valid = e.utf8_error().valid_up_to();
            let lossy = String::from_utf8_lossy(e.as_bytes()).into_owned();
            let file = SourceFile::new(label, lossy);
            let prefix_chars = String::from_utf8_lossy(&e.as_bytes()[..valid]).len();
            return Err(file
                .diagnostic(
                    Span::new(prefix_chars, prefix_chars + 1),
                    "this file is not UTF-8 text",
                )
                .with_help("derivation files are UTF-8 TOML; check that the right file was given")
                .into());
        }
    };
    let file = SourceFile::new(label, text);
    Loader::new(file).run()
}

/// Reads one derivation file given as text (`label` names it in diagnostics), as a part
/// of a whole: its `uses` and `[stated]` may name claims of other files, so they are
/// checked only when files are read together ([`load_texts`], [`load_files`]).
pub fn load_str(label: &str, text: &str) -> Result<DerivationFile, LoadError> {
    Loader::new(SourceFile::new(label, text))
        .run()
        .map(|(f, _)| f)
}

pub(super) struct Loader {
    file: Arc<SourceFile>,
}

impl Loader {
    fn new(file: Arc<SourceFile>) -> Self {
        Loader { file }
    }

    pub(super) fn diag(&self, span: Range<usize>, msg: impl Into<String>) -> Diagnostic {
        self.file.diagnostic(Span::new(span.start, span.end), msg)
    }

    /// The origin of a TOML string value, mapping its characters to file offsets.
    pub(super) fn origin(&self, s: &S) -> Origin {
        Origin {
            file: self.file.clone(),
            map: content_map(&self.file.text, s.span(), s.get_ref()),
        }
    }

    pub(super) fn lang(&self, origin: &Origin, e: LangError) -> Diagnostic {
        let d = origin.diagnostic(e.span, e.message);
        match e.help {
            Some(h) => d.with_help(h),
            None => d,
        }
    }

    fn run(self) -> Result<(DerivationFile, Vec<(String, IdDiag)>), LoadError> {
        if let Some((at, what)) = super::control::first_control(&self.file.text) {
            let end = at
                + self.file.text[at..]
                    .chars()
                    .next()
                    .map_or(1, char::len_utf8);
            return Err(self
                .diag(at..end, format!("{what} is not allowed in a derivation file"))
                .with_help("remove it; a report would show it raw (write LaTeX such as \\beta in '…' strings)")
                .into());
        }
        let raw: RawFile = toml::from_str(&self.file.text).map_err(|e| {
            let span = e.span().unwrap_or(0..0);
            self.diag(
                span,
                format!("malformed derivation file: {}", e.message().trim()),
            )
            .with_help("see `cosserat-check guide`, section \"Derivation files\", for the format")
        })?;
        let decls = Arc::new(self.decls(&raw)?);
        let mut defs = Vec::new();
        for (k, d) in raw.define.iter().enumerate() {
            let def = self.definition(d, &decls, &defs, &raw.define[k + 1..])?;
            defs.push(def);
        }
        let notation = self.notation(&raw.notation, &Notation::default())?;
        let tied = self.tied(&raw, &decls)?;
        let stated = Arc::new(self.stated(&raw.stated, &decls, &defs)?);
        let mut claims = Vec::new();
        let mut ids: Vec<(String, IdDiag)> = Vec::new();
        let mut local_ids = BTreeMap::new();
        for c in &raw.claim {
            let id = c.id.get_ref().clone();
            if id.chars().count() > MAX_ID_CHARS {
                let start = c.id.span().start;
                return Err(self
                    .diag(
                        start..start + 1,
                        format!(
                            "this claim id has {} characters; ids have at most {MAX_ID_CHARS}",
                            id.chars().count()
                        ),
                    )
                    .with_help("ids name a claim in tables and on the command line, like eq33")
                    .into());
            }
            if !valid_id(&id) {
                return Err(self
                    .diag(c.id.span(), format!("`{id}` is not a valid claim id"))
                    .with_help("ids use letters, digits, `-` and `_`, like eq33 or odd-averages")
                    .into());
            }
            if local_ids.insert(id.clone(), ()).is_some() {
                return Err(self
                    .diag(c.id.span(), format!("duplicate claim id `{id}`"))
                    .with_help("every claim id is unique; rename one of them")
                    .into());
            }
            let file = self.file.clone();
            let span = c.id.span();
            ids.push((
                id,
                Box::new(move |m| file.diagnostic(Span::new(span.start, span.end), m)),
            ));
            let mut claim = self.claim(c, (&raw, &tied), &decls, &defs, &notation)?;
            claim.stated = stated.clone();
            claims.push(claim);
        }
        let mut figures = Vec::new();
        for f in &raw.figure {
            if figures.iter().any(|g: &Figure| g.id == *f.id.get_ref()) {
                return Err(self
                    .diag(
                        f.id.span(),
                        format!("duplicate figure id `{}`", f.id.get_ref()),
                    )
                    .with_help("every figure id is unique; rename one of them")
                    .into());
            }
            figures.push(self.figure(f, &raw, &decls, &defs)?);
        }
        Ok((
            DerivationFile {
                paper: self.paper(&raw),
                path: self.file.path.clone(),
                section: raw.section.get_ref().clone(),
                title: raw.title.get_ref().clone(),
                claims,
                stated,
                figures,
                to_complete: self.to_complete(&raw)?,
            },
            ids,
        ))
    }

    /// The symbols a claim says its equation writes first (`introduces`), as ties of
    /// this claim only: each a declared symbol; `None` when it names none.
    fn introduced(
        &self,
        c: &RawClaim,
        decls: &Decls,
    ) -> Result<Option<Vec<(String, TiedSymbol)>>, Diagnostic> {
        if c.introduces.is_empty() {
            return Ok(None);
        }
        let mut out = Vec::new();
        for s in &c.introduces {
            let name = s.get_ref();
            if !decls.symbols.contains_key(name) {
                return Err(self
                    .diag(s.span(), format!("`{name}` is not a declared symbol"))
                    .with_help("`introduces` names declared symbols by their names in the file"));
            }
            out.push((
                name.clone(),
                TiedSymbol {
                    why: "this equation is the first to write it, and may define it".to_owned(),
                    kind: TieKind::Any,
                },
            ));
        }
        Ok(Some(out))
    }

    /// The symbols a drafted file says the paper may tie, each with where and why: each
    /// a declared symbol, each line a line; `None` for a file that is not drafted.
    fn tied(
        &self,
        raw: &RawFile,
        decls: &Decls,
    ) -> Result<Option<Arc<BTreeMap<String, TiedSymbol>>>, Diagnostic> {
        // Checked either way; without `drafted = true` (the declarations checked, every
        // failure decided strictly) it has no effect.
        let mut out = BTreeMap::new();
        for t in &raw.tied {
            let name = t.symbol.get_ref();
            if !decls.symbols.contains_key(name) {
                return Err(self
                    .diag(t.symbol.span(), format!("`{name}` is not a declared symbol"))
                    .with_help("`tied` names declared symbols (scalars, tensors, fields) by their names in the file"));
            }
            let why = t.why.get_ref();
            // The reason is set in a report's sentence, where a backtick would open code.
            if let Some(k) = why.find('`') {
                let at = content_map(&self.file.text, t.why.span(), why)[k];
                return Err(self
                    .diag(
                        at..at + 1,
                        "a backtick in `why` would open code in a report",
                    )
                    .with_help("quote a symbol with \" or ', not a backtick"));
            }
            let why = match &t.line {
                Some(line) if *line.get_ref() < 1 => {
                    return Err(self
                        .diag(line.span(), "a line number is 1 or more")
                        .with_help("the line in the paper's source where the tie may be stated"));
                }
                Some(line) => format!("line {}: {why}", line.get_ref()),
                None => why.clone(),
            };
            let kind = match &t.tie {
                None => TieKind::Any,
                Some(k) => match k.get_ref().as_str() {
                    "trace" => TieKind::Trace,
                    "divergence" => TieKind::Divergence,
                    "law" => TieKind::Law,
                    other => {
                        return Err(self
                            .diag(k.span(), format!("`{other}` is not a kind of tie"))
                            .with_help("`tie = \"trace\"` limits the tie to a zero trace, `tie = \"divergence\"` to a zero trace or a divergence zero at any power, `tie = \"law\"` to sides that read different symbols; without it, any tie counts"))
                    }
                },
            };
            // The first entry of a symbol says why; one that allows more prevails.
            let entry = out.entry(name.clone()).or_insert(TiedSymbol {
                why: why.clone(),
                kind,
            });
            if kind > entry.kind {
                *entry = TiedSymbol { why, kind };
            }
        }
        Ok(raw.drafted.then(|| Arc::new(out)))
    }

    /// The equations `draft` could not read: each id a claim id, each line a line.
    fn to_complete(&self, raw: &RawFile) -> Result<Vec<ToComplete>, Diagnostic> {
        raw.to_complete
            .iter()
            .map(|t| {
                let id = t.id.get_ref();
                if !valid_id(id) {
                    return Err(self
                        .diag(t.id.span(), format!("`{id}` is not a claim id"))
                        .with_help("ids use letters, digits, `-` and `_`, like eq33"));
                }
                let line = usize::try_from(*t.line.get_ref())
                    .ok()
                    .filter(|&l| l >= 1)
                    .ok_or_else(|| {
                        self.diag(t.line.span(), "a line number is 1 or more")
                            .with_help("the equation's line in the paper's source")
                    })?;
                Ok(ToComplete {
                    id: id.clone(),
                    line,
                    reason: t.reason.get_ref().clone(),
                    edit: t.edit.as_ref().map(|e| e.get_ref().clone()),
                })
            })
            .collect()
    }

    /// File-wide assumptions come first, then the check's own. They may read the
    /// file's definitions (`defs`), never a claim's.
    fn file_assumptions_first(
        &self,
        raw: &RawFile,
        decls: &Decls,
        defs: &[Definition],
        check: &mut Check,
    ) -> Result<(), Diagnostic> {
        let mut assumptions = raw
            .assume
            .iter()
            .map(|a| self.assumption(a, decls, defs))
            .collect::<Result<Vec<_>, _>>()?;
        assumptions.append(&mut check.assumptions);
        check.assumptions = assumptions;
        Ok(())
    }

    /// A `[[figure]]`: each curve is read like the side of a claim, with the file's
    /// assumptions, then the figure's `set`, then the curve's, and the figure's box.
    fn figure(
        &self,
        f: &RawFigure,
        raw: &RawFile,
        decls: &Arc<Decls>,
        defs: &[Definition],
    ) -> Result<Figure, Diagnostic> {
        let x = self.grid(&f.x, decls)?;
        if f.curves.is_empty() {
            return Err(self
                .diag(f.id.span(), "a figure needs at least one curve")
                .with_help("curves = [{ y = \"…\", label = \"…\" }]"));
        }
        if f.curves.len() > MAX_CURVES {
            return Err(self
                .diag(
                    f.id.span(),
                    format!(
                        "a figure holds at most {MAX_CURVES} curves, this one {}",
                        f.curves.len()
                    ),
                )
                .with_help("split the curves between figures"));
        }
        let domain = self.param_box(&f.given, decls)?;
        let mut curves = Vec::new();
        for c in &f.curves {
            let mut assume: Vec<S> = f.set.clone();
            assume.extend(c.set.iter().cloned());
            let sides = Some(vec![c.y.clone(), c.y.clone()]);
            let mut check =
                self.check(&f.id, decls, defs, &[], &assume, &sides, &None, false, true)?;
            self.file_assumptions_first(raw, decls, defs, &mut check)?;
            // The range's parameter varies along the curve: an assumption that fixes it
            // would silently make the curve flat.
            if let Some(a) = check.assumptions.iter().find(|a| match a.kind.symbol() {
                Some(s) => s == x.name,
                None => a.reads.contains(&x.name),
            }) {
                return Err(a
                    .origin
                    .diagnostic(
                        crate::lang::Span::new(0, a.text.len()),
                        format!(
                            "`{}` is the figure's parameter; an assumption cannot fix it",
                            x.name
                        ),
                    )
                    .with_help(
                        "remove this assumption for the figure, or plot against another parameter",
                    ));
            }
            check.strategy = Strategy::Exact {
                domain: domain.clone(),
                hypotheses: Vec::new(),
            };
            curves.push(Curve {
                label: c.label.get_ref().clone(),
                text: c.y.get_ref().clone(),
                decls: decls.clone(),
                check,
            });
        }
        Ok(Figure {
            id: f.id.get_ref().clone(),
            title: f.title.get_ref().clone(),
            x_label: f
                .x_label
                .as_ref()
                .map_or_else(|| x.name.clone(), |l| l.get_ref().clone()),
            y_label: f
                .y_label
                .as_ref()
                .map_or_else(String::new, |l| l.get_ref().clone()),
            x,
            curves,
        })
    }

    /// `"f_r = 0.05 .. 3 : 0.05"`: a declared scalar, decimal or rational bounds and
    /// step (100 steps when none is given), at most 10,000 points.
    fn grid(&self, s: &S, decls: &Decls) -> Result<Grid, Diagnostic> {
        let bad = |why: &str| {
            self.diag(s.span(), format!("cannot read `{}` as a range: {why}", s.get_ref()))
                .with_help("write \"f_r = 0.05 .. 3 : 0.05\" (a declared scalar, from .. to, and an optional step)")
        };
        parse_grid(s.get_ref(), decls).map_err(|why| bad(&why.to_string()))
    }

    /// `orders = { voigt = ["11", "22", "12", "21"] }`: each position a string of
    /// components 1..=d, all of one length, none repeated.
    fn orders(
        &self,
        raw: &RawFile,
        dim: usize,
    ) -> Result<BTreeMap<String, Vec<Vec<usize>>>, Diagnostic> {
        let mut out = BTreeMap::new();
        for (name, positions) in &raw.orders {
            let Some(first) = positions.first() else {
                return Err(self
                    .diag(
                        raw.dimension.span(),
                        format!("the order `{name}` has no positions"),
                    )
                    .with_help(
                        "list its positions, e.g. voigt = [\"11\", \"22\", \"12\", \"21\"]",
                    ));
            };
            let valid_name = name.chars().next().is_some_and(|c| c.is_ascii_alphabetic())
                && name.chars().all(|c| c.is_ascii_alphanumeric());
            if !valid_name || RESERVED.contains(&name.as_str()) {
                return Err(self
                    .diag(first.span(), format!("`{name}` cannot name an order"))
                    .with_help("an order's name is letters and digits, starting with a letter, and not a built-in"));
            }
            let width = first.get_ref().len();
            let mut seen: Vec<Vec<usize>> = Vec::with_capacity(positions.len());
            for p in positions {
                let text = p.get_ref();
                let comps: Option<Vec<usize>> = text
                    .chars()
                    .map(|c| {
                        c.to_digit(10)
                            .filter(|&k| (1..=dim as u32).contains(&k))
                            .map(|k| k as usize - 1)
                    })
                    .collect();
                let Some(comps) = comps.filter(|c| !c.is_empty() && c.len() == width) else {
                    return Err(self
                        .diag(p.span(), format!("`{text}` is not a position of {width} component{} in 1..={dim}", if width == 1 { "" } else { "s" }))
                        .with_help("a position is written with one digit per index, as \"12\" for the component 12; all positions of an order have as many"));
                };
                if seen.contains(&comps) {
                    return Err(self
                        .diag(
                            p.span(),
                            format!("position `{text}` occurs twice in the order `{name}`"),
                        )
                        .with_help("each position has one place in an order"));
                }
                seen.push(comps);
            }
            out.insert(name.clone(), seen);
        }
        Ok(out)
    }

    fn decls(&self, raw: &RawFile) -> Result<Decls, Diagnostic> {
        let dim = *raw.dimension.get_ref();
        if !(dim == 2 || dim == 3) {
            return Err(self
                .diag(
                    raw.dimension.span(),
                    format!("dimension must be 2 or 3, not {dim}"),
                )
                .with_help("indices run over 1..3 in space (dimension = 3) or 1..2 in a plane (dimension = 2)"));
        }
        let mut decls = Decls {
            dim: dim as usize,
            normal: None,
            normal_in_plane: raw.normal_in_plane,
            ..Decls::default()
        };
        decls.orders = self.orders(raw, dim as usize)?;
        if raw.normal_in_plane && (dim != 3 || raw.normal.is_none()) {
            let at = raw
                .normal
                .as_ref()
                .map_or(raw.dimension.span(), Spanned::span);
            return Err(self
                .diag(at, "normal_in_plane needs dimension = 3 and a declared normal")
                .with_help("it keeps the normal in the 1-2 plane of a 3D index range (plane Cosserat problems)"));
        }
        let declare = |decls: &mut Decls, name: String, rank: usize, s: &S| {
            if RESERVED.contains(&name.as_str())
                || decls.symbols.contains_key(&name)
                || decls.normal.as_ref() == Some(&name)
            {
                return Err(self
                    .diag(
                        s.span(),
                        format!("`{name}` is declared twice or is a built-in name"),
                    )
                    .with_help(format!(
                        "built-in names: {}; choose another name",
                        RESERVED.join(", ")
                    )));
            }
            let components = assignment_count_saturating(decls.dim, rank);
            if components > MAX_COMPONENTS {
                return Err(self
                    .diag(
                        s.span(),
                        format!(
                            "`{name}` has rank {rank}: {components} components in {}D, more than the {MAX_COMPONENTS} supported",
                            decls.dim
                        ),
                    )
                    .with_help("declare tensors of lower rank"));
            }
            let known = decls.symbols.iter().map(|(k, &r)| (k.as_str(), r));
            if let Some(clash) = read_two_ways(&name, rank, known) {
                return Err(self.diag(s.span(), clash).with_help(
                    "rename one of them: a name's last `_` segment is read as its indices",
                ));
            }
            decls.symbols.insert(name, rank);
            Ok(())
        };
        if let Some(n) = &raw.normal {
            let (base, idx) = self.name_token(n)?;
            if !idx.is_empty() || RESERVED.contains(&base.as_str()) {
                return Err(self
                    .diag(n.span(), "the normal is named without indices, e.g. \"n\"")
                    .with_help("write normal = \"n\" and use it as n_i"));
            }
            decls.normal = Some(base);
        }
        for t in &raw.tensors {
            let (base, idx) = self.name_token(t)?;
            if idx.is_empty() || !distinct_letters(&idx) {
                return Err(self
                    .diag(
                        t.span(),
                        "a tensor is declared with distinct index letters, one per slot",
                    )
                    .with_help("e.g. \"sigma_ij\" for a rank-2 tensor; scalars go in `scalars`"));
            }
            declare(&mut decls, base, idx.len(), t)?;
        }
        for s in &raw.scalars {
            let (_, suffix) = self.name_token(s)?;
            // `x_12` would share its polynomial variable with component 12 of a tensor x.
            if !suffix.is_empty() && suffix.iter().all(char::is_ascii_digit) {
                return Err(self
                    .diag(s.span(), "a scalar's name cannot end in `_` and digits")
                    .with_help("that spelling denotes a tensor component; choose e.g. R_g or h2"));
            }
            declare(&mut decls, s.get_ref().trim().to_owned(), 0, s)?;
        }
        if let Some(p) = &raw.position {
            let (base, idx) = self.name_token(p)?;
            if !idx.is_empty() {
                return Err(self
                    .diag(
                        p.span(),
                        "the position is named without indices, e.g. \"x\"",
                    )
                    .with_help("write position = \"x\" and use it as x_i"));
            }
            declare(&mut decls, base.clone(), 1, p)?;
            decls.position = Some(base);
        }
        for f in &raw.fields {
            let (name, rank, deps) = self.field(f, &decls)?;
            declare(&mut decls, name.clone(), rank, f)?;
            decls.fields.insert(name, deps);
        }
        Ok(decls)
    }

    /// A single name token (`sigma_ij`, `R_g`, `n`): its base and index characters.
    pub(super) fn name_token(&self, s: &S) -> Result<(String, Vec<char>), Diagnostic> {
        self.name_in(&self.origin(s), s.get_ref(), s.span())
    }

    /// A single name token in `text`, which `origin` locates; `whole` is where the
    /// complaint that it is not one name points.
    pub(super) fn name_in(
        &self,
        origin: &Origin,
        text: &str,
        whole: Range<usize>,
    ) -> Result<(String, Vec<char>), Diagnostic> {
        let e = parse_expr(text).map_err(|e| self.lang(origin, e))?;
        match e.kind {
            ExprKind::Name { base, indices, .. } => {
                Ok((base, indices.iter().map(|t| t.ch).collect()))
            }
            _ => Err(self.diag(whole, "expected a single name here, like sigma_ij or R_g")),
        }
    }

    /// One definition of a `define` list; `later` are the ones after it in the same
    /// list, so that a name used before its definition is named as such.
    fn definition(
        &self,
        s: &S,
        decls: &Decls,
        visible: &[Definition],
        later: &[S],
    ) -> Result<Definition, Diagnostic> {
        let origin = self.origin(s);
        let text = s.get_ref();
        let Some(eq) = text.find('=') else {
            return Err(origin
                .diagnostic(Span::new(0, text.len()), "a definition needs `=`")
                .with_help("write it as name_ij = expression, e.g. t_i = sigma_ki n_k"));
        };
        let (name, formal, name_span) = self.lhs_name(&origin, text, eq, Some(decls))?;
        if RESERVED.contains(&name.as_str())
            || decls.symbols.contains_key(&name)
            || decls.normal.as_ref() == Some(&name)
            || visible.iter().any(|d| d.sig.name == name)
        {
            return Err(origin
                .diagnostic(
                    name_span,
                    format!("`{name}` is already declared or defined"),
                )
                .with_help("choose a new name; definitions cannot redefine a name"));
        }
        let known = decls.symbols.iter().map(|(k, &r)| (k.as_str(), r)).chain(
            visible
                .iter()
                .map(|d| (d.sig.name.as_str(), d.sig.formal.len())),
        );
        if let Some(clash) = read_two_ways(&name, formal.len(), known) {
            return Err(origin.diagnostic(name_span, clash).with_help(
                "rename one of them: a name's last `_` segment is read as its indices",
            ));
        }
        let sigs: Vec<DefSig> = visible.iter().map(|d| d.sig.clone()).collect();
        let body = self.rhs(&origin, text, eq, decls, &sigs, later)?;
        if let Some(shape) = body.shape() {
            // A matrix has no indices: its whole left side is its name (`D_el`).
            let whole = text[..eq].trim().to_owned();
            if whole != name
                && (RESERVED.contains(&whole.as_str())
                    || decls.symbols.contains_key(&whole)
                    || visible.iter().any(|d| d.sig.name == whole))
            {
                return Err(origin
                    .diagnostic(
                        name_span,
                        format!("`{whole}` is already declared or defined"),
                    )
                    .with_help("choose a new name; definitions cannot redefine a name"));
            }
            return bounded(Definition::new(
                DefSig {
                    name: whole,
                    formal: Vec::new(),
                    shape: Some(shape),
                },
                body,
                origin,
                text.clone(),
                visible,
            ));
        }
        let shape = None;
        let mut want = formal.clone();
        want.sort_unstable();
        let body = if body.is_literal_zero() {
            body.zero_with_free(&want)
        } else {
            body
        };
        if body.free_letters() != want {
            return Err(origin
                .diagnostic(
                    name_span,
                    format!(
                        "`{name}` {DEFINED_WITH_INDICES} {} but its right side has free indices {}",
                        letters(&formal),
                        letters(&body.free_letters())
                    ),
                )
                .with_help("the defined name carries exactly the free indices of its right side"));
        }
        bounded(Definition::new(
            DefSig {
                name,
                formal,
                shape,
            },
            body,
            origin,
            text.clone(),
            visible,
        ))
    }

    /// The left side of `name_ij = …`: a name with distinct letter indices, or the
    /// whole name of a declared scalar such as `f_g` (when `decls` is given), in a
    /// definition or an assumption.
    fn lhs_name(
        &self,
        origin: &Origin,
        text: &str,
        eq: usize,
        decls: Option<&Decls>,
    ) -> Result<(String, Vec<char>, Span), Diagnostic> {
        let lhs = &text[..eq];
        let sub = sub_origin(origin, 0..eq);
        let e = parse_expr(lhs).map_err(|e| self.lang(&sub, e))?;
        let ExprKind::Name {
            full,
            base,
            indices,
        } = e.kind
        else {
            if matches!(e.kind, ExprKind::Deriv { .. }) {
                return Err(sub
                    .diagnostic(e.span, "a derivative cannot be defined or assumed on its own")
                    .with_help("constrain the field itself (an assumption on a field holds everywhere, so its derivatives follow), or name the value with a scalar"));
            }
            return Err(sub.diagnostic(e.span, "the left side must be a single name such as t_i"));
        };
        // `R_g` declared as a scalar, or `E_lg` when `E` is a scalar (it takes no
        // indices, so the whole token is a name).
        if decls.is_some_and(|d| {
            d.symbols.get(&full) == Some(&0)
                || (!indices.is_empty() && d.symbols.get(&base) == Some(&0))
        }) {
            return Ok((full, Vec::new(), e.span));
        }
        let letters_only = indices.iter().all(|t| t.ch.is_ascii_alphabetic());
        let distinct = indices
            .iter()
            .map(|t| t.ch)
            .collect::<std::collections::BTreeSet<_>>()
            .len()
            == indices.len();
        // (An assumption whose left side is no such name is a constraint.)
        if !letters_only || !distinct {
            return Err(sub
                .diagnostic(e.span, "a defined name carries distinct index letters")
                .with_help("e.g. t_i or mu_ij; fixed components cannot be defined one by one"));
        }
        Ok((base, indices.iter().map(|t| t.ch).collect(), e.span))
    }

    /// The right side of `name = expression`; `later` are the definitions after this
    /// one in its list, so that a name used before its definition is named as such.
    fn rhs(
        &self,
        origin: &Origin,
        text: &str,
        eq: usize,
        decls: &Decls,
        defs: &[DefSig],
        later: &[S],
    ) -> Result<crate::lang::Node, Diagnostic> {
        let rhs_text = &text[eq + 1..];
        let sub = sub_origin(origin, eq + 1..text.len());
        let e = parse_expr(rhs_text).map_err(|e| self.lang(&sub, e))?;
        Scope { decls, defs }.check(&e).map_err(|e| {
            let later = e
                .unknown
                .as_deref()
                .and_then(|u| self.defined_later(u, later));
            let d = self.lang(&sub, e);
            match later {
                Some(help) => d.with_help(help),
                None => d,
            }
        })
    }

    /// The help for a name used before its definition further down the same list.
    fn defined_later(&self, name: &str, later: &[S]) -> Option<String> {
        let s = later.iter().find(|s| {
            let text = s.get_ref();
            let lhs = text.split('=').next().unwrap_or_default().trim();
            lhs.split('_').next() == Some(name)
        })?;
        let line = self.file.line_col(s.span().start).0;
        Some(format!(
            "`{name}` is defined later, at line {line}; definitions are read in order, so \
             move its definition above this one"
        ))
    }

    /// `X_13 = expr`: a fixed component of a declared symbol. `None` when the left side
    /// is not a name with digit indices only.
    fn component_assumption(
        &self,
        origin: &Origin,
        text: &str,
        eq: usize,
        decls: &Decls,
        sigs: &[DefSig],
    ) -> Result<Option<AssumptionKind>, Diagnostic> {
        let sub = sub_origin(origin, 0..eq);
        let Ok(e) = parse_expr(&text[..eq]) else {
            return Ok(None);
        };
        let ExprKind::Name { base, indices, .. } = e.kind else {
            return Ok(None);
        };
        if indices.is_empty() || !indices.iter().all(|t| t.ch.is_ascii_digit()) {
            return Ok(None);
        }
        if decls.symbols.get(&base) != Some(&indices.len()) {
            return Err(sub
                .diagnostic(e.span, format!("`{base}` is not a declared tensor of rank {}", indices.len()))
                .with_help("a component assumption such as sigma_13 = 0 fixes one component of a declared tensor"));
        }
        let mut index = Vec::with_capacity(indices.len());
        for t in &indices {
            let d = t.ch.to_digit(10).unwrap_or(0) as usize;
            if d == 0 || d > decls.dim {
                return Err(sub.diagnostic(
                    t.span,
                    format!("fixed index {d} is outside 1..={}", decls.dim),
                ));
            }
            index.push(d - 1);
        }
        let body = self.rhs(origin, text, eq, decls, sigs, &[])?;
        no_matrix(origin, &body, "an assumption")?;
        if !body.free.is_empty() {
            return Err(origin.diagnostic(
                Span::new(eq + 1, text.len()),
                "a single component is set to a scalar expression",
            ));
        }
        Ok(Some(AssumptionKind::Component {
            symbol: base,
            index,
            body,
        }))
    }

    /// `left = right` whose left side is no single name (`s_kk = 0`,
    /// `s_ij s_ij = 2 tau^2`): a constraint between expressions, for every value of
    /// their free indices. `None` when the left side is a name to be assumed.
    fn expression_constraint(
        &self,
        origin: &Origin,
        text: &str,
        eq: usize,
        decls: &Decls,
        sigs: &[DefSig],
    ) -> Result<Option<AssumptionKind>, Diagnostic> {
        let sub = sub_origin(origin, 0..eq);
        let Ok(e) = parse_expr(&text[..eq]) else {
            return Ok(None);
        };
        // A name with distinct letters, or a declared scalar, is assumed itself; a
        // definition's name is read as its value (`lap = 0` with lap = phi_,kk).
        if let ExprKind::Name {
            full,
            base,
            indices,
            ..
        } = &e.kind
        {
            let letters: BTreeSet<char> = indices.iter().map(|t| t.ch).collect();
            let distinct = letters.len() == indices.len()
                && indices.iter().all(|t| t.ch.is_ascii_alphabetic());
            let defined = sigs.iter().any(|d| d.name == *base || d.name == *full);
            if (distinct && !defined) || decls.symbols.get(full) == Some(&0) {
                return Ok(None);
            }
        }
        let left = Scope { decls, defs: sigs }
            .check(&e)
            .map_err(|e| self.lang(&sub, e))?;
        // `sigma_ij,j = 0`, `w_i,jk = 0`: a zero right side is the zero tensor of the
        // left side's free indices, every component of the left side zero.
        let zero = text[eq + 1..].trim() == "0" && !left.free.is_empty();
        let right = if zero {
            let span = Span::new(0, eq);
            let times = crate::lang::parser::Expr {
                kind: ExprKind::Mul(
                    Box::new(crate::lang::parser::Expr {
                        kind: ExprKind::Number(Rational::int(0)),
                        span,
                    }),
                    Box::new(e.clone()),
                ),
                span,
            };
            Scope { decls, defs: sigs }
                .check(&times)
                .map_err(|e| self.lang(&sub, e))?
        } else {
            self.rhs(origin, text, eq, decls, sigs, &[])?
        };
        no_matrix(&sub, &left, "a constraint")?;
        no_matrix(origin, &right, "a constraint")?;
        if left.free_letters() != right.free_letters() {
            return Err(origin.diagnostic(
                Span::new(0, text.len()),
                format!(
                    "the sides of this constraint have free indices {} and {}",
                    letters(&left.free_letters()),
                    letters(&right.free_letters())
                ),
            )
            .with_help("both sides take the same free indices: the constraint holds for every value of them"));
        }
        Ok(Some(AssumptionKind::Constraint { left, right }))
    }

    /// One assumption; its right side may read the definitions in scope.
    pub(super) fn assumption(
        &self,
        s: &S,
        decls: &Decls,
        defs: &[Definition],
    ) -> Result<Assumption, Diagnostic> {
        let origin = self.origin(s);
        let sigs: Vec<DefSig> = defs.iter().map(|d| d.sig.clone()).collect();
        let kind = self.assumption_kind(&origin, s.get_ref(), decls, &sigs)?;
        let reads: BTreeSet<String> = super::reads::reachable(kind.bodies(), defs)
            .0
            .into_iter()
            .flat_map(|n| n.symbols())
            .map(str::to_owned)
            .collect();
        // An assumption gives each symbol one value per state: a right side that
        // varies with the normal (outside avg) would be read at one normal only, and
        // one that varies with position at one point, unless the symbol is a field.
        if let AssumptionKind::Component { symbol, body, .. }
        | AssumptionKind::Equals { symbol, body, .. } = &kind
        {
            use super::reads::{varies_with, Varies};
            match varies_with(body, defs, decls) {
                Some(Varies::Normal) => {
                    return Err(origin
                        .diagnostic(
                            body.span,
                            format!("an assumption gives `{symbol}` one value per state, but this right side varies with the normal"),
                        )
                        .with_help(format!("define `{symbol}` instead (define = [\"…\"]), or average the right side with avg(…)")))
                }
                Some(Varies::Position) if !decls.varies(symbol) => {
                    return Err(origin
                        .diagnostic(
                            body.span,
                            format!("`{symbol}` does not vary with position, but this right side does"),
                        )
                        .with_help(format!("declare `{symbol}` in `fields`, or define it instead")))
                }
                _ => {}
            }
        }
        let kind = match kind {
            AssumptionKind::Constraint { left, right } => {
                Self::constraint_or_differential(&origin, left, right, defs, decls)?
            }
            kind => kind,
        };
        // A field declared on some coordinates only (`w_i(x_2)`) keeps that
        // restriction only while nothing replaces, eliminates or ties it.
        let restricted = kind
            .symbol()
            .map(str::to_owned)
            .into_iter()
            .chain(reads.iter().cloned())
            .find_map(|s| {
                let free = decls.fields.get(&s)?.iter().position(|d| !d)?;
                Some((s, free + 1))
            });
        if let Some((field, k)) = restricted {
            let rank = decls.symbols.get(&field).copied().unwrap_or(0);
            let slots: String = "ijklmnpq".chars().take(rank).collect();
            return Err(origin
                .diagnostic(
                    Span::new(0, s.get_ref().len()),
                    format!("`{field}` depends on some coordinates only, and an assumption that mentions it would lose that"),
                )
                .with_help(format!("declare `{field}` on every coordinate and state what it does not depend on as a hypothesis (`{field}_{slots},{k} = 0`)")));
        }
        Ok(Assumption {
            kind,
            text: s.get_ref().trim().to_owned(),
            origin,
            reads,
        })
    }

    /// A constraint between expressions relates values of one state; one that reads a
    /// derivative of a field, and varies with nothing else, is a differential
    /// hypothesis that holds at every point (`phi_,kk = 0`).
    fn constraint_or_differential(
        origin: &Origin,
        left: Node,
        right: Node,
        defs: &[Definition],
        decls: &Decls,
    ) -> Result<AssumptionKind, Diagnostic> {
        use super::reads::{differentiates_fields, varies_with, Varies};
        let varies = [&left, &right].map(|side| (side.span, varies_with(side, defs, decls)));
        if let Some((span, _)) = varies.iter().find(|(_, v)| *v == Some(Varies::Normal)) {
            return Err(origin
                .diagnostic(*span, "a constraint between expressions relates values of one state, but this side varies with the normal")
                .with_help("constrain symbols that are not fields and do not read the normal; relate a field with X = expression"));
        }
        if varies.iter().all(|(_, v)| v.is_none()) {
            return Ok(AssumptionKind::Constraint { left, right });
        }
        if !differentiates_fields(&left, defs) && !differentiates_fields(&right, defs) {
            let span = varies
                .iter()
                .find(|(_, v)| v.is_some())
                .map_or(left.span, |(span, _)| *span);
            return Err(origin
                .diagnostic(span, "a constraint between expressions relates values of one state, but this side varies with position")
                .with_help("relate a field with X = expression (u_i = A_ij x_j), or state a differential hypothesis on its derivatives (phi_,kk = 0)"));
        }
        Ok(AssumptionKind::Differential { left, right })
    }

    fn assumption_kind(
        &self,
        origin: &Origin,
        text: &str,
        decls: &Decls,
        sigs: &[DefSig],
    ) -> Result<AssumptionKind, Diagnostic> {
        if let Some(eq) = text.find('=') {
            if let Some(component) = self.component_assumption(origin, text, eq, decls, sigs)? {
                return Ok(component);
            }
            if let Some(constraint) = self.expression_constraint(origin, text, eq, decls, sigs)? {
                return Ok(constraint);
            }
            let (name, formal, span) = self.lhs_name(origin, text, eq, Some(decls))?;
            match decls.symbols.get(&name) {
                Some(&rank) if rank == formal.len() => {}
                Some(&rank) => {
                    return Err(origin.diagnostic(
                        span,
                        format!("`{name}` has rank {rank}, so it takes {rank} indices here"),
                    ))
                }
                None => {
                    return Err(origin
                        .diagnostic(span, format!("`{name}` is not a declared symbol"))
                        .with_help(
                            "an assumption constrains a symbol from `tensors` or `scalars`",
                        ))
                }
            }
            let body = self.rhs(origin, text, eq, decls, sigs, &[])?;
            no_matrix(origin, &body, "an assumption")?;
            let mut want = formal.clone();
            want.sort_unstable();
            if body.free_letters() != want {
                return Err(origin.diagnostic(
                    span,
                    format!(
                        "the right side has free indices {}, not {}",
                        letters(&body.free_letters()),
                        letters(&formal)
                    ),
                ));
            }
            return Ok(AssumptionKind::Equals {
                symbol: name,
                formal,
                body,
            });
        }
        let trimmed = text.trim();
        let parsed = trimmed
            .strip_suffix(')')
            .and_then(|t| t.split_once('('))
            .map(|(f, a)| (f.trim(), a.trim()));
        let usage = "write traceless(X), symmetric(X), antisymmetric(X), X = expression or X_13 = expression";
        let Some((func, arg)) = parsed else {
            return Err(origin
                .diagnostic(Span::new(0, text.len()), "unrecognised assumption")
                .with_help(usage));
        };
        let lead = text.len() - text.trim_start().len();
        let arg_at = lead + trimmed.find('(').unwrap_or(0) + 1;
        let arg_span = Span::new(arg_at, arg_at + arg.len().max(1));
        if decls.symbols.get(arg) != Some(&2) {
            return Err(origin
                .diagnostic(arg_span, format!("`{arg}` is not a declared rank-2 tensor"))
                .with_help(
                    "these assumptions apply to a symbol declared in `tensors`, e.g. \"s_ij\"",
                ));
        }
        let symbol = arg.to_owned();
        match func {
            "traceless" => Ok(AssumptionKind::Traceless { symbol }),
            "symmetric" => Ok(AssumptionKind::Symmetric { symbol }),
            "antisymmetric" => Ok(AssumptionKind::Antisymmetric { symbol }),
            _ => Err(origin
                .diagnostic(
                    Span::new(lead, lead + func.len().max(1)),
                    format!("unknown assumption `{func}`"),
                )
                .with_help(usage)),
        }
    }

    #[allow(clippy::too_many_arguments)]
    fn check(
        &self,
        anchor: &S,
        decls: &Decls,
        defs: &[Definition],
        define: &[S],
        assume: &[S],
        sides: &Option<Vec<S>>,
        chains: &Option<Vec<Vec<S>>>,
        verbatim: bool,
        needs_sides: bool,
    ) -> Result<Check, Diagnostic> {
        let mut defs = defs.to_vec();
        for (k, d) in define.iter().enumerate() {
            let def = self.definition(d, decls, &defs, &define[k + 1..])?;
            defs.push(def);
        }
        let assumptions = assume
            .iter()
            .map(|a| self.assumption(a, decls, &defs))
            .collect::<Result<Vec<_>, _>>()?;
        let raw_chains: Vec<&Vec<S>> = match (sides, chains) {
            (Some(s), None) => vec![s],
            (None, Some(c)) => c.iter().collect(),
            (Some(_), Some(_)) => {
                return Err(self
                    .diag(anchor.span(), "give either `sides` or `chains`, not both")
                    .with_help(
                        "`sides` is one chain a = b = …; `chains` is a list of such chains",
                    ))
            }
            (None, None) if !needs_sides => Vec::new(),
            (None, None) => {
                return Err(self
                    .diag(
                        anchor.span(),
                        "this statement has no `sides` (or `chains`) to check",
                    )
                    .with_help("add sides = [\"left\", \"right\"] in index notation"))
            }
        };
        if raw_chains.is_empty() && needs_sides {
            return Err(self.diag(anchor.span(), "`chains` is empty"));
        }
        let sigs: Vec<DefSig> = defs.iter().map(|d| d.sig.clone()).collect();
        let scope = Scope { decls, defs: &sigs };
        let mut out = Vec::new();
        for chain in raw_chains {
            if chain.len() < 2 {
                let at = chain.first().map_or(anchor.span(), Spanned::span);
                return Err(self
                    .diag(at, "an equation chain needs at least two sides")
                    .with_help("write sides = [\"left\", \"right\"]"));
            }
            let mut checked: Vec<Side> = Vec::new();
            for s in chain {
                let origin = self.origin(s);
                let e = parse_expr(s.get_ref()).map_err(|e| self.lang(&origin, e))?;
                let node = match scope.check(&e) {
                    Ok(n) => Ok(n),
                    Err(e) if verbatim && e.kind == ErrorKind::Index => Err(e),
                    Err(e) => return Err(self.lang(&origin, e)),
                };
                if let (Some(Side { node: Ok(prev), .. }), Ok(cur)) = (checked.last(), &node) {
                    if !verbatim && !prev.matches_free_indices(cur) {
                        return Err(origin
                            .diagnostic(
                                Span::new(0, s.get_ref().len()),
                                format!(
                                    "{DIFFERENT_FREE_INDICES}: {} on the left, {} here",
                                    letters(&prev.free_letters()),
                                    letters(&cur.free_letters())
                                ),
                            )
                            .with_help("both sides of an equation carry the same free indices; for a printed statement that does not, set verbatim = true"));
                    }
                }
                checked.push(Side {
                    text: s.get_ref().clone(),
                    origin,
                    node,
                    entry: None,
                });
            }
            out.push(checked);
        }
        let out = entrywise(out, &mut defs)?;
        Ok(Check {
            defs,
            assumptions,
            chains: out,
            verbatim,
            drafted: None,
            strategy: Strategy::Exact {
                domain: ParamBox::default(),
                hypotheses: Vec::new(),
            },
        })
    }

    /// A proportionality or a sign claim compares exactly two sides: one factor, or one
    /// difference, for one pair.
    fn one_pair_if_needed(&self, c: &RawClaim, check: &Check) -> Result<(), Diagnostic> {
        let pair = check.chains.len() == 1 && check.chains[0].len() == 2;
        let help = match (&check.strategy, &c.strategy) {
            (Strategy::Proportional { .. }, Some(at)) if !pair => (
                at,
                "strategy = \"proportional\"",
                "left = λ · right for one nonzero factor λ",
            ),
            (Strategy::Scalar { claim, .. }, Some(at))
                if !pair
                    && matches!(**claim, ScalarClaim::Sign(_) | ScalarClaim::SignExactly(..)) =>
            {
                (
                    at,
                    "strategy = \"sign\"",
                    "left − right has the sign of `relation`",
                )
            }
            _ => return Ok(()),
        };
        // Matrix sides are compared entry by entry, one chain per entry.
        if check.chains.iter().flatten().any(|s| s.entry.is_some()) {
            let instead = if matches!(check.strategy, Strategy::Proportional { .. }) {
                "decide the matrix equation with the factor written out (the default strategy), or declare the matrices as tensors and write the sides in index notation"
            } else {
                "compare one entry (A[1,2]) or a scalar of the matrices (det(A), trace(A))"
            };
            return Err(self
                .diag(
                    help.0.span(),
                    format!("{} compares two sides that are not matrices", help.1),
                )
                .with_help(instead));
        }
        Err(self
            .diag(
                help.0.span(),
                format!("{} compares exactly two sides", help.1),
            )
            .with_help(format!("write sides = [\"left\", \"right\"]: {}", help.2)))
    }

    /// A correction's own `function`, for the claim kinds that have one.
    fn corrected_function(
        &self,
        r: &super::raw::RawCorrection,
        check: &mut Check,
        decls: &Decls,
    ) -> Result<(), Diagnostic> {
        let Some(text) = &r.function else {
            return Ok(());
        };
        let sigs: Vec<_> = check.defs.iter().map(|d| d.sig.clone()).collect();
        let corrected = self.expression(text, decls, &sigs, &[])?;
        let target = match &mut check.strategy {
            Strategy::Scalar { claim, .. } => match &mut **claim {
                ScalarClaim::Monotone { function, .. }
                | ScalarClaim::Limit { function, .. }
                | ScalarClaim::Roots { function, .. } => Some(function),
                ScalarClaim::Sign(_)
                | ScalarClaim::SignExactly(..)
                | ScalarClaim::Stationary(_) => None,
            },
            _ => None,
        };
        match target {
            Some(function) => {
                *function = corrected;
                Ok(())
            }
            None => Err(self
                .diag(
                    text.span(),
                    "`function` in a correction applies to monotone, limit and roots claims",
                )
                .with_help("a correction of other claims gives its own `sides`")),
        }
    }

    fn verdict(&self, s: &S) -> Result<Verdict, Diagnostic> {
        Verdict::parse(s.get_ref()).ok_or_else(|| {
            self.diag(s.span(), format!("unknown verdict `{}`", s.get_ref()))
                .with_help("expect is one of \"holds\", \"fails\", \"conditional\", \"undecided\"")
        })
    }

    /// The work a file's claims are credited to: its `paper = …`, or, without one,
    /// "untitled derivations: FILE" (a user's file never inherits another paper's name).
    fn paper(&self, raw: &RawFile) -> String {
        match &raw.paper {
            Some(p) => p.get_ref().clone(),
            None => format!("untitled derivations: {}", self.file.path),
        }
    }

    /// The chains of a statement without `sides` (a claim's, or its correction's): its
    /// printed statement as read, every reading of every chain, in the context of its
    /// own `define` and `assume` (`context`) after `defs`. Conditions and inequalities
    /// need explicit sides.
    fn chains_from_reading(
        &self,
        input: Printed<'_>,
        context: (&S, &[S], &[S], bool),
        decls: &Decls,
        defs: &[Definition],
        file: &Notation,
    ) -> Result<Vec<Vec<S>>, Diagnostic> {
        let (anchor, define, assume, verbatim) = context;
        let probe = self.check(
            anchor, decls, defs, define, assume, &None, &None, verbatim, false,
        )?;
        let input = Printed {
            prose: false,
            declared: &None,
            ..input
        };
        let t = self.transcript(&input, file, decls, &probe, Vec::new(), Vec::new())?;
        let help = "give sides = [\"left\", \"right\"] in index notation, or make the printed statement readable (`cosserat-check guide`, \"Reading the printed statement\")";
        let reading = t.reading.map_err(|u| {
            let col = crate::lang::latex::column(input.printed.get_ref(), u.span.start);
            self.diag(
                input.printed.span(),
                format!(
                    "this statement has no `sides`, and its printed LaTeX cannot be read at column {col}: {}",
                    u.message
                ),
            )
            .with_help(help)
        })?;
        let mut chains = Vec::new();
        for part in &reading.parts {
            if part.condition
                || part
                    .relations
                    .iter()
                    .any(|r| *r != crate::lang::latex::Rel::Eq)
            {
                return Err(self
                    .diag(
                        input.printed.span(),
                        format!(
                            "this statement has no `sides`, and `{}` is a condition or an inequality, which need explicit sides and hypotheses",
                            part.latex
                        ),
                    )
                    .with_help(help));
            }
            for route in &part.routes {
                chains.push(
                    route
                        .iter()
                        .map(|m| Spanned::new(input.printed.span(), m.text.clone()))
                        .collect(),
                );
            }
        }
        Ok(chains)
    }

    /// A notation table: the superscript declarations first (they change how keys
    /// read), then the symbols; `within` gives how the keys of a claim's table read.
    fn notation(
        &self,
        table: &BTreeMap<String, Spanned<NotationValue>>,
        within: &Notation,
    ) -> Result<Notation, Diagnostic> {
        let mut out = Notation::within(within);
        let (sups, symbols): (Vec<_>, Vec<_>) = table.iter().partition(|(k, _)| k.starts_with('^'));
        for (key, value) in sups.into_iter().chain(symbols) {
            out.add(key, value.get_ref().values()).map_err(|e| {
                self.diag(value.span(), e.message)
                    .with_help("a notation entry maps one printed symbol to the language: '\\sigma_{ij}^{(1)}' = \"sig1_ij\"; see `cosserat-check guide`, \"Reading the printed statement\"")
            })?;
        }
        Ok(out)
    }

    /// What the transcription check needs: the printed statement read through the
    /// claim's and the file's notation, and the chains as written.
    fn transcript(
        &self,
        input: &Printed<'_>,
        file: &Notation,
        decls: &Decls,
        check: &Check,
        written: Vec<Vec<String>>,
        conditions: Vec<String>,
    ) -> Result<Transcript, Diagnostic> {
        let Printed {
            printed,
            prose,
            table,
            defines,
            declared,
        } = *input;
        let notation = self.notation(table, file)?.then(file);
        let defines = defines
            .iter()
            .map(|d| {
                notation::defined_symbol(d.get_ref(), &notation)
                    .map_err(|e| self.diag(d.span(), e.message))
            })
            .collect::<Result<Vec<_>, _>>()?;
        let sigs: Vec<DefSig> = check.defs.iter().map(|d| d.sig.clone()).collect();
        let reading = if prose {
            Err(notation::Unread {
                span: Span::new(0, 0),
                message: "a sentence of prose is not read".to_owned(),
            })
        } else {
            notation::read(printed.get_ref(), &notation, &defines, decls, &sigs)
        };
        Ok(Transcript {
            reading,
            written,
            declared: declared.as_ref().map(|d| d.get_ref().clone()),
            conditions,
            from_reading: false,
            prose,
            notation: Arc::new(notation),
        })
    }

    fn claim(
        &self,
        c: &RawClaim,
        (raw, tied): (&RawFile, &Option<Arc<BTreeMap<String, TiedSymbol>>>),
        decls: &Arc<Decls>,
        defs: &[Definition],
        notation: &Notation,
    ) -> Result<Claim, Diagnostic> {
        let expect = match &c.expect {
            Some(e) => Some((self.verdict(e)?, e.span())),
            None => None,
        };
        if let Some((expect, span)) = expect
            .clone()
            .filter(|(e, _)| *e != Verdict::Holds && c.reason.is_none())
        {
            return Err(self
                .diag(span, format!("a claim expected to be `{expect}` needs a `reason`"))
                .with_help("add reason = \"…\": one sentence saying why the printed statement does not hold"));
        }
        let needs_sides = c.strategy.as_ref().is_none_or(|s| {
            matches!(
                s.get_ref().as_str(),
                "exact" | "proportional" | "numeric" | "sign"
            )
        });
        // Without sides, a statement whose printed LaTeX can be read is decided on the
        // reading itself.
        let read_chains = if needs_sides && !c.prose && c.sides.is_none() && c.chains.is_none() {
            let context = (&c.id, &c.define[..], &c.assume[..], c.verbatim);
            Some(self.chains_from_reading(Printed::of_claim(c), context, decls, defs, notation)?)
        } else {
            None
        };
        let chains = read_chains.clone().or_else(|| c.chains.clone());
        let mut check = self.check(
            &c.id,
            decls,
            defs,
            &c.define,
            &c.assume,
            &c.sides,
            &chains,
            c.verbatim,
            needs_sides,
        )?;
        check.strategy = self.strategy(c, decls, &check.defs)?;
        let introduced = self.introduced(c, decls)?;
        check.drafted = match tied {
            // The claim's table, then the file's: it names a tie's symbols as printed.
            Some(tied) => Some(Drafted {
                notation: Arc::new(self.notation(&c.notation, notation)?.then(notation)),
                tied: match introduced {
                    Some(mine) => {
                        let mut all = (**tied).clone();
                        for (name, t) in mine {
                            all.entry(name).or_insert(t).kind = TieKind::Any;
                        }
                        Arc::new(all)
                    }
                    None => tied.clone(),
                },
            }),
            None => None,
        };
        self.one_pair_if_needed(c, &check)?;
        self.file_assumptions_first(raw, decls, defs, &mut check)?;
        let correction = match &c.correction {
            None => None,
            Some(r) => {
                let expect = self.verdict(&r.expect)?;
                // The claim's `defines` hold for its correction too, with its own.
                let defines: Vec<S> = c.defines.iter().chain(&r.defines).cloned().collect();
                let input = Printed {
                    printed: &r.printed,
                    prose: c.prose,
                    table: &r.notation,
                    defines: &defines,
                    declared: &r.differs_from_printed,
                };
                // The correction's own entries, then the claim's, then the file's.
                let table = self.notation(&c.notation, notation)?.then(notation);
                // Without sides, a correction is decided on its reading, as a claim is.
                let read_chains = (needs_sides
                    && !c.prose
                    && r.sides.is_none()
                    && r.chains.is_none()
                    && r.function.is_none())
                .then(|| {
                    let context = (&r.printed, &r.define[..], &r.assume[..], r.verbatim);
                    self.chains_from_reading(input, context, decls, &check.defs, &table)
                })
                .transpose()?;
                let chains = read_chains.clone().or_else(|| r.chains.clone());
                // The correction sees the claim's definitions and assumptions too.
                let mut inner = self.check(
                    &r.printed,
                    decls,
                    &check.defs,
                    &r.define,
                    &r.assume,
                    &r.sides,
                    &chains,
                    r.verbatim,
                    needs_sides,
                )?;
                inner.strategy = check.strategy.clone();
                inner.drafted = tied.as_ref().map(|tied| Drafted {
                    notation: Arc::new(table.clone()),
                    tied: tied.clone(),
                });
                self.corrected_function(r, &mut inner, decls)?;
                self.one_pair_if_needed(c, &inner)?;
                let mut assumptions = check.assumptions.clone();
                assumptions.append(&mut inner.assumptions);
                inner.assumptions = assumptions;
                let transcript = self.transcript(
                    &input,
                    &table,
                    decls,
                    &inner,
                    written(&r.sides, &r.chains),
                    conditions(c),
                )?;
                let transcript = Transcript {
                    from_reading: read_chains.is_some(),
                    ..transcript
                };
                Some(Correction {
                    statement: r.printed.get_ref().clone(),
                    reason: r.reason.get_ref().clone(),
                    expect,
                    check: inner,
                    transcript,
                })
            }
        };
        let transcript = self.transcript(
            &Printed::of_claim(c),
            notation,
            decls,
            &check,
            written(&c.sides, &chains),
            conditions(c),
        )?;
        let transcript = Transcript {
            from_reading: read_chains.is_some(),
            ..transcript
        };
        Ok(Claim {
            transcript,
            paper: self.paper(raw),
            id: c.id.get_ref().clone(),
            origin: self.origin(&c.id),
            section: c.section.as_ref().unwrap_or(&raw.section).get_ref().clone(),
            statement: c.printed.get_ref().clone(),
            prose: c.prose,
            declared: expect.is_some(),
            expect: expect.map_or(Verdict::Holds, |(e, _)| e),
            reason: c.reason.as_ref().map(|r| r.get_ref().clone()),
            note: c.note.as_ref().map(|r| r.get_ref().clone()),
            decls: decls.clone(),
            check,
            correction,
            uses: c
                .uses
                .iter()
                .map(|u| Use {
                    id: u.get_ref().clone(),
                    origin: self.origin(u),
                })
                .collect(),
            stated: Arc::default(),
        })
    }

    /// The `[stated]` table: each entry names a definition of the file, the claim whose
    /// statement it transcribes, and optionally its corrected form, a definition of the
    /// same name and indices read in the scope of the definitions before it.
    fn stated(
        &self,
        raw: &BTreeMap<String, Spanned<RawStated>>,
        decls: &Decls,
        defs: &[Definition],
    ) -> Result<Vec<Stated>, Diagnostic> {
        let mut out = Vec::new();
        for (name, entry) in raw {
            let e = entry.get_ref();
            let Some(k) = defs.iter().position(|d| d.sig.name == *name) else {
                return Err(self
                    .diag(entry.span(), format!("`{name}` is not a definition of this file"))
                    .with_help("[stated] keys are the names of the file's `define` entries, like mut for mut_ij"));
            };
            let corrected = match &e.corrected {
                None => None,
                Some(c) => {
                    let def = self.definition(c, decls, &defs[..k], &[])?;
                    let original = &defs[k].sig;
                    if def.sig.name != original.name
                        || def.sig.formal != original.formal
                        || def.sig.shape != original.shape
                    {
                        return Err(self
                            .diag(c.span(), format!("the corrected form must define `{}` as it is defined", defs[k].text.split('=').next().unwrap_or_default().trim()))
                            .with_help("write the same left side, e.g. corrected = \"mut_ij = …\" for mut_ij"));
                    }
                    Some(def)
                }
            };
            out.push(Stated {
                name: name.clone(),
                by: e.by.get_ref().clone(),
                origin: self.origin(&e.by),
                corrected,
            });
        }
        Ok(out)
    }
}

/// A printed statement with what the transcription check reads it with.
#[derive(Clone, Copy)]
struct Printed<'a> {
    printed: &'a S,
    prose: bool,
    /// The statement's own notation entries.
    table: &'a BTreeMap<String, Spanned<NotationValue>>,
    defines: &'a [S],
    declared: &'a Option<S>,
}

impl<'a> Printed<'a> {
    fn of_claim(c: &'a RawClaim) -> Self {
        Printed {
            printed: &c.printed,
            prose: c.prose,
            table: &c.notation,
            defines: &c.defines,
            declared: &c.differs_from_printed,
        }
    }
}

/// A claim's hypotheses as written: its `given` and `domain`.
fn conditions(c: &RawClaim) -> Vec<String> {
    c.given
        .iter()
        .chain(&c.domain)
        .map(|s| s.get_ref().clone())
        .collect()
}

/// A claim's chains as written.
fn written(sides: &Option<Vec<S>>, chains: &Option<Vec<Vec<S>>>) -> Vec<Vec<String>> {
    let text = |c: &Vec<S>| c.iter().map(|s| s.get_ref().clone()).collect();
    match (sides, chains) {
        (Some(s), _) => vec![text(s)],
        (None, Some(c)) => c.iter().map(text).collect(),
        (None, None) => Vec::new(),
    }
}

fn valid_id(id: &str) -> bool {
    !id.is_empty()
        && id
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '-' || c == '_')
}

/// The complaint when a new name can be read two ways: a scalar `E_lg` where `E` has
/// rank 2 (is it E with indices l, g?), or a tensor `E` of rank 2 where a scalar `E_lg`
/// exists. `known` lists the names already declared or defined, with their ranks.
fn read_two_ways<'k>(
    name: &str,
    rank: usize,
    mut known: impl Iterator<Item = (&'k str, usize)>,
) -> Option<String> {
    let clash = |scalar: &str, base: &str, r: usize| {
        let suffix: Vec<String> = scalar[base.len() + 1..].chars().map(String::from).collect();
        format!(
            "`{scalar}` could also be read as `{base}` (rank {r}) with indices {}",
            suffix.join(", ")
        )
    };
    if rank == 0 {
        let (base, suffix) = name.rsplit_once('_')?;
        let (_, r) = known.find(|&(k, r)| k == base && r == suffix.len() && r > 0)?;
        Some(clash(name, base, r))
    } else {
        let (scalar, _) = known.find(|&(k, r)| {
            r == 0
                && k.rsplit_once('_')
                    .is_some_and(|(b, suffix)| b == name && suffix.len() == rank)
        })?;
        Some(clash(scalar, name, rank))
    }
}

/// Refuses a matrix where a scalar or tensor expression is expected.
pub(super) fn no_matrix(origin: &Origin, node: &Node, what: &str) -> Result<(), Diagnostic> {
    match node.shape() {
        Some(shape) => Err(origin
            .diagnostic(
                node.span,
                format!(
                    "{what} takes a scalar or a tensor, but this is {}",
                    shape_words(shape)
                ),
            )
            .with_help("read a scalar off a matrix with det(…), trace(…) or A[i,j]")),
        None => Ok(()),
    }
}

/// A chain of matrices is decided entry by entry: one scalar chain per entry, each
/// side read off the matrix as `(side)[i,j]`. A side that is not already a matrix
/// definition becomes a claim-local one (named so that no file can write it), so that
/// each side's matrix is computed once for all its entries.
pub(super) fn entrywise(
    chains: Vec<Vec<Side>>,
    defs: &mut Vec<Definition>,
) -> Result<Vec<Vec<Side>>, Diagnostic> {
    let mut out = Vec::with_capacity(chains.len());
    for (ci, chain) in chains.into_iter().enumerate() {
        let shapes: Vec<Option<(usize, usize)>> = chain
            .iter()
            .map(|s| s.node.as_ref().ok().and_then(Node::shape))
            .collect();
        let Some(shape) = shapes.iter().flatten().next().copied() else {
            out.push(chain);
            continue;
        };
        // The literal 0 stands for the zero matrix of the chain's shape (`A - A^T = 0`).
        let zero = |k: usize| chain[k].node.as_ref().is_ok_and(|n| n.is_literal_zero());
        if let Some(k) = (0..chain.len()).find(|&k| shapes[k] != Some(shape) && !zero(k)) {
            let side = &chain[k];
            let what = shapes[k].map_or_else(|| "a scalar or tensor".to_owned(), shape_words);
            return Err(side
                .origin
                .diagnostic(
                    Span::new(0, side.text.len()),
                    format!("this side is {what}, and the first matrix side {}", shape_words(shape)),
                )
                .with_help("both sides of a matrix equation have one shape; compare a scalar with det(…), trace(…) or A[i,j]"));
        }
        let mut matrices = Vec::with_capacity(chain.len());
        for (si, side) in chain.iter().enumerate() {
            let node = side
                .node
                .as_ref()
                .expect("a side with a shape, or the literal 0, is well-formed");
            if zero(si) {
                matrices.push(None);
                continue;
            }
            let reference = match &node.kind {
                NodeKind::Matrix {
                    op: MatrixOp::Def(_),
                    ..
                } => node.clone(),
                _ => {
                    let name = format!("side {}.{}", ci + 1, si + 1);
                    defs.push(Definition::new(
                        DefSig {
                            name: name.clone(),
                            formal: Vec::new(),
                            shape: Some(shape),
                        },
                        node.clone(),
                        side.origin.clone(),
                        format!("{name} = {}", side.text.trim()),
                        defs,
                    ));
                    Node {
                        kind: NodeKind::Matrix {
                            rows: shape.0,
                            cols: shape.1,
                            op: MatrixOp::Def(name),
                        },
                        free: Vec::new(),
                        bound: Vec::new(),
                        span: node.span,
                    }
                }
            };
            matrices.push(Some(reference));
        }
        for i in 0..shape.0 {
            for j in 0..shape.1 {
                let at = if shape.1 == 1 {
                    format!("[{}]", i + 1)
                } else {
                    format!("[{},{}]", i + 1, j + 1)
                };
                let sides = chain
                    .iter()
                    .zip(&matrices)
                    .map(|(side, m)| {
                        let Some(m) = m else {
                            // Every entry of the zero matrix is the literal 0.
                            return Side {
                                entry: Some((i, j)),
                                ..side.clone()
                            };
                        };
                        let text = side.text.trim();
                        let plain = text.chars().all(|c| c.is_ascii_alphanumeric() || c == '_');
                        Side {
                            text: if plain {
                                format!("{text}{at}")
                            } else {
                                format!("({text}){at}")
                            },
                            origin: side.origin.clone(),
                            node: Ok(Node {
                                kind: NodeKind::Read(MatrixRead::Entry(i, j), Box::new(m.clone())),
                                free: Vec::new(),
                                bound: Vec::new(),
                                span: m.span,
                            }),
                            entry: Some((i, j)),
                        }
                    })
                    .collect();
                out.push(sides);
            }
        }
    }
    Ok(out)
}

/// The most points a figure's range may have.
const MAX_POINTS: usize = 10_000;
/// The most curves one figure draws (each evaluated at every point of the grid).
pub const MAX_CURVES: usize = 16;

/// Why a range of a figure could not be read.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum GridError {
    #[error("no `=` between the parameter and its range")]
    NoEquals,
    #[error("`{0}` is not a declared scalar")]
    NotScalar(String),
    #[error("no `..` between the bounds")]
    NoDots,
    #[error("`{0}` is not a number")]
    NotNumber(String),
    #[error("the range is empty (`to` must exceed `from`)")]
    Empty,
    #[error("the step must be positive")]
    Step,
    #[error("the step is longer than the range: a curve needs two points")]
    LongStep,
    #[error("more than {MAX_POINTS} points")]
    TooMany,
}

/// Reads `NAME = FROM .. TO [: STEP]` (also the `--x` of `plot`, without spaces).
pub fn parse_grid(text: &str, decls: &Decls) -> Result<Grid, GridError> {
    let (name, range) = text.split_once('=').ok_or(GridError::NoEquals)?;
    let name = name.trim();
    if decls.symbols.get(name).is_none_or(|&rank| rank != 0) {
        return Err(GridError::NotScalar(name.to_owned()));
    }
    let (bounds, step) = match range.split_once(':') {
        Some((b, st)) => (b, Some(st.trim())),
        None => (range, None),
    };
    let (from, to) = bounds.split_once("..").ok_or(GridError::NoDots)?;
    let number = |t: &str| {
        let t = t.trim();
        let (n, d) = t.split_once('/').unwrap_or((t, "1"));
        let (n, d) = (n.trim(), d.trim());
        let minus = n.strip_prefix('-');
        let n = crate::lang::parser::parse_decimal(minus.unwrap_or(n));
        let n = if minus.is_some() { n.map(|x| -x) } else { n };
        n.zip(crate::lang::parser::parse_decimal(d))
            .and_then(|(n, d)| n.checked_div(&d))
            .ok_or_else(|| GridError::NotNumber(t.to_owned()))
    };
    let (from, to) = (number(from)?, number(to)?);
    if to <= from {
        return Err(GridError::Empty);
    }
    let span = &to - &from;
    let step = match step {
        Some(st) => number(st)?,
        None => span
            .checked_div(&Rational::int(100))
            .expect("100 is not zero"),
    };
    if step.is_negative() || step.is_zero() {
        return Err(GridError::Step);
    }
    let steps =
        crate::algebra::rational::floor(&span.checked_div(&step).expect("the step is not zero"));
    if steps < Rational::int(1) {
        return Err(GridError::LongStep);
    }
    if steps >= Rational::int(MAX_POINTS as i64) {
        return Err(GridError::TooMany);
    }
    let count = steps.to_f64() as usize;
    let values = (0..=count)
        .map(|k| &from + &(&step * &Rational::int(k as i64)))
        .collect();
    Ok(Grid {
        name: name.to_owned(),
        values,
    })
}
