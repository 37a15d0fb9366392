//! Binding for [`crate::nc::stream`]: the `NcStream` class, an NC program
//! given chunk by chunk (`push(Uint8Array)`, a file read through
//! `file.stream()`), then checked (`checkNc`) or simulated
//! (`simulateToolPathColumns`) as the whole-text calls of the same names
//! do, with the same options; the whole text is never in wasm memory.

use wasm_bindgen::prelude::*;

use super::convert::{
    callback_arg, got, not_reentered, opt_number_arg, reserve, NC_BYTES_PER_TEXT_BYTE,
};
use super::toolpath::{check_obj, columns_sim, parse_options, sim_config, sim_program, take_key};
use crate::nc::program::{Keep, Program};
use crate::nc::NcErrors;

#[wasm_bindgen(typescript_custom_section)]
const TS: &str = r#"
/** The options of NcStream's checkNc: NcParseOptions without files (a stream is the main program alone). */
export type NcStreamParseOptions = Omit<NcParseOptions, 'files'>;
/** The config of NcStream's simulateToolPathColumns: ToolPathConfig without files. */
export type NcStreamToolPathConfig = Omit<ToolPathConfig, 'files'>;
"#;

/// The wasm memory reserved ahead of the bytes pushed, in steps of this
/// (when no `totalBytes` was given): the allocator otherwise grows the
/// memory 64 KiB at a time (see [`reserve`]).
const RESERVE_AHEAD: usize = 128 << 20;

/// An NC program read chunk by chunk: `push` each chunk of its bytes
/// (UTF-8; invalid bytes are read as U+FFFD, as `File.text()` reads
/// them), then call one of `checkNc` and `simulateToolPathColumns`, which
/// give what the whole-text functions of the same names give for the
/// whole text. `push` throws when the text is over a budget (naming the
/// line) or is no text file; after a finishing call the stream is spent.
#[wasm_bindgen]
pub struct NcStream {
    inner: Option<crate::nc::stream::NcStream>,
    /// Bytes pushed.
    pushed: usize,
    /// Bytes of text the memory was reserved for.
    reserved_for: usize,
    /// The chunk copied into wasm memory (one buffer for every push).
    chunk: Vec<u8>,
}

#[wasm_bindgen]
impl NcStream {
    /// A stream with nothing read. `totalBytes` (optional): the text's
    /// length if known (a file's size), to reserve the wasm memory its
    /// reading takes at once, as the whole-text calls do.
    #[wasm_bindgen(constructor)]
    pub fn new(
        #[wasm_bindgen(unchecked_optional_param_type = "number")] total_bytes: JsValue,
    ) -> Result<NcStream, JsError> {
        not_reentered()?;
        let total = match opt_number_arg(&total_bytes, "totalBytes")? {
            None => 0,
            Some(n) if n < 0.0 => {
                return Err(JsError::new(&format!(
                    "totalBytes: expected the text's length in bytes, a number ≥ 0, got {n}"
                )))
            }
            Some(n) => {
                crate::budget::check_bytes("program", n as u64)?;
                n as usize
            }
        };
        reserve(total.saturating_mul(NC_BYTES_PER_TEXT_BYTE));
        Ok(NcStream {
            inner: Some(crate::nc::stream::NcStream::with_size_hint(total as u64)),
            pushed: 0,
            reserved_for: total,
            chunk: Vec::new(),
        })
    }

    /// Reads the next chunk of the text's bytes (any cut: a line or a
    /// character may be split between chunks). Throws an `Error` naming
    /// the line when the text is over a budget, or when it is no text
    /// file (an image, a PDF, an archive).
    pub fn push(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "Uint8Array")] chunk: JsValue,
    ) -> Result<(), JsError> {
        not_reentered()?;
        let Some(a) = chunk.dyn_ref::<js_sys::Uint8Array>() else {
            return Err(JsError::new(&format!(
                "chunk: expected a Uint8Array, got {}",
                got(&chunk)
            )));
        };
        let n = a.length() as usize;
        // a chunk itself over the budget is refused before it is copied
        crate::budget::check_bytes("chunk", n as u64)?;
        if self.inner.is_none() {
            return Err(spent());
        }
        self.pushed += n;
        if self.pushed > self.reserved_for {
            self.reserved_for = self.pushed + RESERVE_AHEAD / NC_BYTES_PER_TEXT_BYTE;
            reserve(RESERVE_AHEAD);
        }
        let mut chunk = std::mem::take(&mut self.chunk);
        chunk.resize(n, 0);
        a.copy_to(&mut chunk);
        let read = self.stream()?.push(&chunk);
        self.chunk = chunk;
        read.map_err(|e| JsError::new(&e.to_string()))
    }

    /// Ends the text and checks the program as `checkNc` checks a whole
    /// text: every error, or the warnings and the summary (`NcCheck`).
    /// `options` as `checkNc`'s, without `files`.
    #[wasm_bindgen(js_name = checkNc, unchecked_return_type = "NcCheck")]
    pub fn check_nc(
        &mut self,
        #[wasm_bindgen(unchecked_optional_param_type = "NcStreamParseOptions")] options: JsValue,
    ) -> Result<JsValue, JsError> {
        not_reentered()?;
        let opts = parse_options(no_files(options, "options")?)?;
        let (read, not_read) = self.take()?.finish_noting_refusal(&opts, Keep::Motion);
        check_obj(read, not_read)
    }

    /// Ends the text and simulates the program as
    /// `simulateToolPathColumns` simulates a whole text (throws its first
    /// error). `config` as that call's, without `files`;
    /// `onProgress(fraction, 'simulating')` likewise.
    #[wasm_bindgen(
        js_name = simulateToolPathColumns,
        unchecked_return_type = "ToolPathSimulationColumns"
    )]
    pub fn simulate_tool_path_columns(
        &mut self,
        #[wasm_bindgen(unchecked_param_type = "NcStreamToolPathConfig")] config: JsValue,
        #[wasm_bindgen(unchecked_optional_param_type = "Function | null")] on_progress: JsValue,
    ) -> Result<JsValue, JsError> {
        not_reentered()?;
        let (opts, cfg) = sim_config(no_files(config, "config")?)?;
        let on_progress = callback_arg(on_progress, "onProgress")?;
        let read: Result<Program, NcErrors> = self.take()?.finish(&opts, Keep::Motion);
        columns_sim(sim_program(read, 0)?, &cfg, &on_progress)
    }
}

impl NcStream {
    fn stream(&mut self) -> Result<&mut crate::nc::stream::NcStream, JsError> {
        self.inner.as_mut().ok_or_else(spent)
    }

    /// The stream, to finish: the chunk buffer is freed first (left in
    /// wasm memory, it would split the room the lexed blocks leave, which
    /// the simulation's large blocks use).
    fn take(&mut self) -> Result<crate::nc::stream::NcStream, JsError> {
        self.chunk = Vec::new();
        self.inner.take().ok_or_else(spent)
    }
}

fn spent() -> JsError {
    JsError::new(
        "this NcStream has been checked or simulated already: make a new NcStream to read a program again",
    )
}

/// `options` without a `files` key, which a stream does not read.
fn no_files(options: JsValue, what: &str) -> Result<JsValue, JsError> {
    let (files, rest) = take_key(options, "files")?;
    if !files.is_undefined() {
        return Err(JsError::new(&format!(
            "{what}.files: an NcStream reads the main program alone; give the subprogram files with the whole text to checkNc or simulateToolPathColumns, or paste them after M30 in the program"
        )));
    }
    Ok(rest)
}
