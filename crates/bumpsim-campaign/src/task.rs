//! A point's task: the script both executors run (`run-point.sh
//! POINT_FOLDER`, POSIX `sh`), and the exit marker it leaves in the point
//! folder when the solver ends (`.bumpsim-exit`: `exit N`, and on Slurm
//! `restarts N`, the task's `SLURM_RESTART_COUNT`), written atomically
//! (temporary file, rename) so that a controller — this one or a restarted
//! one — learns the outcome even when it was not the solver's parent.

use crate::state::Point;
use std::path::Path;

/// The task script in the campaign folder.
pub const TASK_SCRIPT: &str = "run-point.sh";
/// The file a task writes when the solver ends.
pub const EXIT_MARKER: &str = ".bumpsim-exit";

/// The task script: runs `command` in the point folder given as `$1`
/// (output in `solver.log`) and records its exit status in [`EXIT_MARKER`].
///
/// ```
/// let script = bumpsim_campaign::task::task_script(&["ccx".into(), "-i".into(), "deck".into()]);
/// assert!(script.contains("'ccx' '-i' 'deck' > solver.log 2>&1\n"));
/// ```
pub fn task_script(command: &[String]) -> String {
    let words: Vec<String> = command.iter().map(|w| quote(w)).collect();
    format!(
        "#!/bin/sh\n# written by bumpsim campaign init: runs one point's solver in its folder\n\
         cd \"$1\" || exit 97\n\
         rm -f {EXIT_MARKER} {EXIT_MARKER}.tmp\n\
         {} > solver.log 2>&1\n\
         status=$?\n\
         printf 'exit %s\\nrestarts %s\\n' \"$status\" \"${{SLURM_RESTART_COUNT:-0}}\" > {EXIT_MARKER}.tmp \
         && mv -f {EXIT_MARKER}.tmp {EXIT_MARKER}\n\
         exit \"$status\"\n",
        words.join(" ")
    )
}

/// A word quoted for `sh` (single quotes).
pub fn quote(word: &str) -> String {
    format!("'{}'", word.replace('\'', "'\\''"))
}

/// What a task recorded when its solver ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Marker {
    /// The solver's exit status.
    pub code: i32,
    /// How often Slurm had requeued the task (0 elsewhere).
    pub restarts: u32,
}

/// The exit marker of a point's task, if it wrote one.
pub fn marker(dir: &Path, point: &Point) -> Option<Marker> {
    let text = std::fs::read_to_string(dir.join(&point.folder).join(EXIT_MARKER)).ok()?;
    parse_marker(&text)
}

fn parse_marker(text: &str) -> Option<Marker> {
    let mut lines = text.lines();
    let code = lines
        .next()?
        .trim()
        .strip_prefix("exit ")?
        .trim()
        .parse()
        .ok()?;
    let restarts = lines
        .find_map(|l| l.trim().strip_prefix("restarts ")?.trim().parse().ok())
        .unwrap_or(0);
    Some(Marker { code, restarts })
}

/// Why a solver with exit status `code` failed; above 128 the shell's code
/// for a signal (SIGTERM is what scancel, time limits and pre-emption send).
pub fn exit_reason(code: i32) -> String {
    match code {
        143 => "solver killed by signal 15, SIGTERM (exit code 143: cancelled, timed out or pre-empted?)".into(),
        129..=192 => format!("solver killed by signal {} (exit code {code})", code - 128),
        _ => format!("solver exit code {code}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markers_of_both_forms_are_read() {
        let m = |code, restarts| Some(Marker { code, restarts });
        assert_eq!(parse_marker("exit 0\n"), m(0, 0));
        assert_eq!(parse_marker("exit 143\nrestarts 2\n"), m(143, 2));
        assert_eq!(parse_marker("exit \n"), None);
        assert_eq!(parse_marker("exi"), None);
    }

    #[test]
    fn the_script_records_the_status_and_the_restarts() {
        let dir = std::env::temp_dir().join(format!("bumpsim-task-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("p")).unwrap();
        let script = dir.join(TASK_SCRIPT);
        std::fs::write(
            &script,
            task_script(&["sh".into(), "-c".into(), "exit 3".into()]),
        )
        .unwrap();
        let status = std::process::Command::new("sh")
            .arg(&script)
            .arg(dir.join("p"))
            .env("SLURM_RESTART_COUNT", "1")
            .status()
            .unwrap();
        assert_eq!(status.code(), Some(3));
        let marker = std::fs::read_to_string(dir.join("p").join(EXIT_MARKER)).unwrap();
        assert_eq!(
            parse_marker(&marker),
            Some(Marker {
                code: 3,
                restarts: 1
            })
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
