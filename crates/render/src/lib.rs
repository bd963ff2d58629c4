//! Light transport: acceleration structures, cameras, sampling, integrators, film.
//! Being built; see issue 4.
