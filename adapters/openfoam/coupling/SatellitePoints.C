#include "SatellitePoints.H"
#include "error.H"

Foam::cosim::SatellitePoints::SatellitePoints(label divisions)
{
    if (divisions < 1 || divisions > 9)
    {
        FatalErrorInFunction
            << "voidage_divisions must be between 1 and 9, got " << divisions
            << exit(FatalError);
    }

    // Fine sampling points per sub-cube edge: enough for shares to ~1e-4
    const label fine = 48;
    const scalar subEdge = 2.0/divisions;
    const scalar h = subEdge/fine;

    DynamicList<vector> offsets;
    DynamicList<scalar> weights;

    for (label i = 0; i < divisions; ++i)
    for (label j = 0; j < divisions; ++j)
    for (label k = 0; k < divisions; ++k)
    {
        const vector corner(-1 + i*subEdge, -1 + j*subEdge, -1 + k*subEdge);
        label count = 0;
        vector sum(Zero);
        for (label a = 0; a < fine; ++a)
        for (label b = 0; b < fine; ++b)
        for (label c = 0; c < fine; ++c)
        {
            const vector x = corner + vector((a + 0.5)*h, (b + 0.5)*h, (c + 0.5)*h);
            if (magSqr(x) <= 1.0)
            {
                ++count;
                sum += x;
            }
        }
        if (count > 0)
        {
            offsets.append(sum/count);
            weights.append(scalar(count));
        }
    }

    scalar total = 0;
    forAll(weights, i)
    {
        total += weights[i];
    }
    forAll(weights, i)
    {
        weights[i] /= total;
    }

    // Turn the pattern by a fixed oblique rotation (Rodrigues, axis (1 2 3), 0.6 rad) so that no
    // two satellites share an x, y or z: on the axis-aligned faces of a blockMesh mesh a parcel
    // then crosses a face one satellite at a time, not a whole layer at once. A rotation keeps
    // every satellite inside the sphere and the weights unchanged.
    const vector k = vector(1, 2, 3)/Foam::sqrt(14.0);
    const scalar theta = 0.6;
    const scalar c = Foam::cos(theta), sn = Foam::sin(theta);
    forAll(offsets, i)
    {
        const vector& v = offsets[i];
        offsets[i] = v*c + (k ^ v)*sn + k*(k & v)*(1 - c);
    }

    offsets_.transfer(offsets);
    weights_.transfer(weights);
}
