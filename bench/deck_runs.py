"""Runs a study's variants of one deck side by side (the bench/ study scripts share it)."""
import concurrent.futures


def run_variants(run, variants, jobs):
    """Calls run(name, arguments) for every variant, 'jobs' at a time; returns {name: values},
    or None after printing each failed variant's error (values holding an "error" key)."""
    with concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        futures = [pool.submit(run, name, arguments) for name, arguments in variants.items()]
        results = dict(future.result() for future in futures)
    failed = [name for name in variants if "error" in results[name]]
    for name in failed:
        print(f"{name}: failed: {results[name]['error']}")
    return None if failed else results
