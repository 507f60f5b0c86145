//! Field declarations: `fields = ["u_i", "theta", "v_i(x_2)"]`. A field is a tensor
//! that varies with the position; by default it depends on every coordinate, and a
//! list in parentheses restricts it to some (a simple-shear layer where everything
//! depends on x_2 only). Derivatives with respect to the other coordinates are zero.

use super::load::{distinct_letters, Loader};
use super::raw::S;
use crate::lang::{Decls, Diagnostic, Span};

impl Loader {
    /// One field declaration: its name, rank, and the coordinates it depends on.
    pub(super) fn field(
        &self,
        f: &S,
        decls: &Decls,
    ) -> Result<(String, usize, Vec<bool>), Diagnostic> {
        let text = f.get_ref();
        let origin = self.origin(f);
        let (head, deps) = match text.find('(') {
            None => (text.as_str(), None),
            Some(open) => (&text[..open], Some(open)),
        };
        let at =
            |start: usize, end: usize, msg: String| origin.diagnostic(Span::new(start, end), msg);
        let (base, idx) = self.name_in(&origin, head, f.span())?;
        if !distinct_letters(&idx) {
            return Err(at(
                0,
                head.len(),
                "a field is declared with distinct index letters, one per slot".into(),
            )
            .with_help("e.g. \"u_i\" for a vector field, \"theta\" for a scalar field"));
        }
        let dim = decls.dim;
        let Some(open) = deps else {
            return Ok((base, idx.len(), vec![true; dim]));
        };
        let Some(close) = text
            .rfind(')')
            .filter(|&c| c > open && text[c + 1..].trim().is_empty())
        else {
            return Err(at(
                open,
                open + 1,
                "this `(` of the coordinate list is never closed".into(),
            )
            .with_help("write e.g. \"v_i(x_2)\" or \"theta(x_1, x_2)\""));
        };
        let Some(position) = &decls.position else {
            return Err(at(
                open,
                close + 1,
                "a coordinate list needs a declared position".into(),
            )
            .with_help("add position = \"x\" at the top of the file"));
        };
        let mut on = vec![false; dim];
        let mut offset = open + 1;
        for part in text[open + 1..close].split(',') {
            let start = offset + (part.len() - part.trim_start().len());
            let end = start + part.trim().len();
            offset += part.len() + 1;
            let coordinate = part
                .trim()
                .strip_prefix(position.as_str())
                .and_then(|rest| rest.strip_prefix('_'))
                .and_then(|k| k.parse::<usize>().ok())
                .filter(|k| (1..=dim).contains(k));
            let Some(k) = coordinate else {
                return Err(at(
                    start,
                    end.max(start + 1),
                    format!("`{}` is not a coordinate", part.trim()),
                )
                .with_help(format!("coordinates are {position}_1 … {position}_{dim}")));
            };
            if on[k - 1] {
                return Err(at(start, end, format!("{position}_{k} is listed twice")));
            }
            on[k - 1] = true;
        }
        Ok((base, idx.len(), on))
    }
}
