//! `signorini` command line: parse arguments, call the library, map errors
//! to exit codes (0 success, 1 error in the input or the solve, 2 usage).

use clap::{Parser, Subcommand};
use std::path::PathBuf;
use std::process::ExitCode;

#[derive(Parser)]
#[command(
    name = "signorini",
    version,
    about = "Nonlinear 3D contact mechanics by finite elements"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Solve a case: write a VTU per converged increment, a .pvd series,
    /// summary.json and convergence.svg.
    Run {
        /// The TOML case file.
        case: PathBuf,
        /// Output folder (default: the case's [output].folder, else
        /// `results` beside the case file).
        #[arg(long)]
        output: Option<PathBuf>,
        /// Worker threads for assembly and factorisation (default: all cores).
        #[arg(long, value_parser = clap::value_parser!(u32).range(1..))]
        threads: Option<u32>,
        /// No progress bar and no log lines.
        #[arg(long)]
        quiet: bool,
    },
    /// Validate the case and its mesh without solving; print what was read.
    Check {
        /// The TOML case file.
        case: PathBuf,
    },
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Run {
            case,
            output,
            threads,
            quiet,
        } => run(case, output, threads, quiet),
        Command::Check { case } => check(case),
    };
    match result {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {e}");
            ExitCode::from(1)
        }
    }
}

fn run(
    case: PathBuf,
    output: Option<PathBuf>,
    threads: Option<u32>,
    quiet: bool,
) -> signorini::Result<()> {
    if let Some(t) = threads {
        // Only fails if a pool already exists, which cannot happen here.
        let _ = rayon::ThreadPoolBuilder::new()
            .num_threads(t as usize)
            .build_global();
    }
    let options = signorini::run::RunOptions { output, quiet };
    let outcome = signorini::run::run(&case, &options)?;
    if !quiet {
        let s = &outcome.summary;
        println!(
            "done: {} increments, {} Newton iterations in {:.2} s; results in {}",
            s.increments.len(),
            s.increments.iter().map(|i| i.iterations).sum::<usize>(),
            s.wall_time,
            outcome.output_dir.display()
        );
    }
    Ok(())
}

fn check(case: PathBuf) -> signorini::Result<()> {
    let loaded = signorini::case::load(&case)?;
    let problem = loaded.build_problem()?;
    let requests = loaded.output_requests(&problem)?;
    let mesh = &problem.model.mesh;
    for note in &loaded.notes {
        println!("note: {note}");
    }
    println!("case      {}", case.display());
    println!("nodes     {}", mesh.num_nodes());
    println!("elements  {}", mesh.elements.len());
    println!(
        "dofs      {} ({} prescribed)",
        problem.model.num_dofs(),
        problem.constrained_dofs().iter().filter(|&&c| c).count()
    );
    println!("regions:");
    for r in &mesh.regions {
        println!("  {:<20} {} elements", r.name, r.elements.len());
    }
    println!("surface sets:");
    for s in &mesh.surfaces {
        println!(
            "  {:<20} {} facets, {} nodes",
            s.name,
            s.facets.len(),
            mesh.surface_nodes(s).len()
        );
    }
    if !mesh.node_sets.is_empty() {
        println!("node sets:");
        for s in &mesh.node_sets {
            println!("  {:<20} {} nodes", s.name, s.nodes.len());
        }
    }
    for f in &problem.nodal_forces {
        println!(
            "nodal force on '{}': {:?} on each of its {} nodes",
            f.set,
            f.force,
            f.nodes.len()
        );
    }
    if !problem.contacts.is_empty() {
        println!("contacts:");
        for c in &problem.contacts {
            println!(
                "  {:<20} surface '{}' ({} secondary nodes), {:?}, h = {:.3e}",
                c.name,
                c.surface,
                c.nodes.len(),
                c.law,
                c.element_size
            );
        }
    }
    println!("steps:");
    for s in &problem.steps {
        println!("  {:<20} to t = {}", s.name, s.end_time);
    }
    for h in &requests.histories {
        println!(
            "history   {}: {} {}",
            h.name,
            h.label,
            h.location(&mesh.nodes)
        );
    }
    for p in &requests.profiles {
        println!(
            "profile   {}: {} nodes of interface '{}'",
            p.name,
            p.nodes.len(),
            p.interface_name
        );
    }
    println!("ok: the case is valid");
    Ok(())
}
