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

    offsets_.transfer(offsets);
    weights_.transfer(weights);
}
